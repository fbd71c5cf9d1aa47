// vs11 asm, vs11 disasm, vs11 validate.
#include <cstdio>
#include <memory>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "vm/asm/bytecode.h"
#include "vm/asm/disassembler.h"
#include "vm/cli/cli_support.h"
#include "vm/cli/commands.h"
#include "vm/core/atomic_file.h"
#include "vm/reference/program_metadata.h"

namespace vs11::cli {
namespace {

// One diagnostic for `vs11 validate --json`: the parts that are known, and its code's stable name.
nlohmann::json DiagnosticJson(const Diagnostic& diagnostic) {
  nlohmann::json entry = {{"severity", std::string(kSeverityNames.Name(diagnostic.severity))},
                          {"code", DiagnosticCodeName(diagnostic.code)},
                          {"message", diagnostic.message}};
  if (!diagnostic.loc.file.empty()) entry["file"] = diagnostic.loc.file;
  if (diagnostic.loc.line > 0) entry["line"] = diagnostic.loc.line;
  if (diagnostic.loc.column > 0) entry["column"] = diagnostic.loc.column;
  if (diagnostic.word_offset >= 0) entry["word"] = diagnostic.word_offset;
  return entry;
}

// {"file", "valid", "diagnostics": [...], and for a valid program "instructions" and "slots"} on stdout.
void PrintValidationJson(const std::string& path, const ProgramFlags& flags) {
  ProgramForVerify loaded = LoadProgramForVerify(path, flags.ToOptions(), flags.FragmentFlag());
  nlohmann::json diagnostics = nlohmann::json::array();
  for (const Diagnostic& diagnostic : loaded.diagnostics.all()) diagnostics.push_back(DiagnosticJson(diagnostic));
  nlohmann::json report = {{"file", path}, {"valid", loaded.program.has_value()}, {"diagnostics", diagnostics}};
  if (loaded.program) {
    ProgramStats stats = ComputeStats(*loaded.program);
    report["instructions"] = stats.instructions;
    report["slots"] = stats.slots;
  }
  std::printf("%s\n", report.dump(2).c_str());
  if (!loaded.program) throw CommandFailure{1};
}

}  // namespace

void AddAsmCommand(CLI::App& app) {
  struct Args {
    std::string input, output;
    ProgramFlags flags;
  };
  auto args = std::make_shared<Args>();
  CLI::App* command = app.add_subcommand("asm", "Assemble a .vsh source into D3D9 vs_1_1 bytecode (.vso)");
  command->footer(
      "The source is run through a C preprocessor first (#define, #include, #if, #line).\n"
      "DX9 (vs_1_1, dcl_*) and DX8 (vs.1.1, c[a0.x + n]) syntax are both accepted.\n"
      "Errors are printed as FILE:LINE:COL: error: MESSAGE [code]; on error no output file is written.\n"
      "A DX8 program that reads temporary lanes nothing wrote is assembled with a warning (the lanes read 0);\n"
      "--strict refuses it, as DX9 vs_1_1 always does.\n\n"
      "Examples:\n  vs11 asm programs/sh9_irradiance.vsh -o sh9.vso -D CV_BASE=4");
  command->add_option("input", args->input, "Source file (.vsh; - reads standard input)")->required();
  command->add_option("-o,--output", args->output, "Bytecode file to write")->required();
  args->flags.AddTo(*command);
  command->callback([args] {
    CheckInputsAndOutputs({args->input}, {args->output});
    Program program = LoadProgramOrFail(args->input, args->flags);
    std::vector<std::uint8_t> bytes = BytesFromWords(Encode(program));
    if (const Status written = WriteFileAtomically(args->output, bytes); !written) Fail(written.message());
  });
}

void AddDisasmCommand(CLI::App& app) {
  struct Args {
    std::string input, output;
  };
  auto args = std::make_shared<Args>();
  CLI::App* command = app.add_subcommand("disasm", "Print vs_1_1 bytecode as DX9 assembly that re-assembles identically");
  command->footer("Malformed streams are rejected with the word offset of the bad token.\n\n"
                  "Examples:\n  vs11 disasm sh9.vso");
  command->add_option("input", args->input, "Bytecode file (.vso; - reads standard input)")->required();
  command->add_option("-o,--output", args->output, "Write the text here instead of stdout");
  command->callback([args] {
    CheckInputsAndOutputs({args->input}, {args->output});
    ProgramFlags flags;
    flags.skip_validation = true;  // disassembly shows what is there, valid or not
    LoadedProgram loaded = LoadProgram(args->input, flags.ToOptions());
    if (loaded.program && !loaded.from_bytecode) {
      Fail(fmt::format("{}: not a bytecode file (it does not start with a vertex-shader version token, vs_1_0 to vs_3_0)", args->input));
    }
    std::fputs(loaded.diagnostics.ToString().c_str(), stderr);
    if (!loaded.program) throw CommandFailure{1};
    std::string text = Disassemble(*loaded.program);
    if (args->output.empty()) {
      std::fputs(text.c_str(), stdout);
    } else if (const Status written = WriteFileAtomically(args->output, text); !written) {
      Fail(written.message());
    }
  });
}

void AddValidateCommand(CLI::App& app) {
  struct Args {
    std::string input;
    ProgramFlags flags;
    bool json = false;
  };
  auto args = std::make_shared<Args>();
  CLI::App* command = app.add_subcommand("validate", "Check a .vsh or .vso program against the D3D vs_1_1 rules");
  command->footer("Exit status 0 when valid (warnings allowed), 1 otherwise. Each message ends with its code in\n"
                  "brackets, e.g. [uninitialized-lanes]. A DX8 (vs.1.1) program that reads temporary lanes nothing\n"
                  "wrote gets a warning (the lanes read 0); --strict makes that an error, as it always is in DX9.\n\n"
                  "Examples:\n  vs11 validate programs/sh9_irradiance.vsh\n"
                  "  vs11 validate --strict programs/sh9_irradiance.vsh\n"
                  "  vs11 validate --json programs/sh9_irradiance.vsh");
  command->add_option("input", args->input, "Program (.vsh source or .vso bytecode; - reads standard input)")->required();
  command->add_flag("--json", args->json,
                    "Print {file, valid, diagnostics: [{severity, code, message, file, line, column, word}], "
                    "instructions, slots} on stdout instead of text");
  args->flags.AddTo(*command, /*offer_skip_validation=*/false);
  command->callback([args] {
    if (args->json) {
      PrintValidationJson(args->input, args->flags);
      return;
    }
    Program program = LoadProgramOrFail(args->input, args->flags);
    ProgramStats stats = ComputeStats(program);
    std::printf("%s: valid %s: %d instructions, %d slots\n", args->input.c_str(),
                std::string(ShaderModelName(program.model())).c_str(), stats.instructions, stats.slots);
  });
}

}  // namespace vs11::cli
