#include "vm/cli/cli_support.h"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <filesystem>
#include <limits>

#include <fmt/format.h>

#include "vm/cli/choice_option.h"
#include "vm/cli/commands.h"
#include "vm/cli/parse_command_line.h"
#include "vm/core/input_file.h"
#include "vm/core/thread_pool.h"
#include "vm/engines/engine_factory.h"
#include "vm/gl/gl_context.h"
#include "vm/gl/gl_engine.h"
#include "vm/reference/program_metadata.h"

namespace vs11::cli {

void ProgramFlags::AddTo(CLI::App& command, bool offer_skip_validation) {
  command.add_option("-I,--include", include_dirs, "Folder searched for #include files (after the includer's folder)");
  command.add_option("-D,--define", defines, "Preprocessor definition NAME or NAME=VALUE");
  if (offer_skip_validation) {
    command.add_flag("--skip-validation", skip_validation,
                     "Accept anything that is syntactically vs_1_1 (like D3DXSHADER_SKIPVALIDATION)");
  }
  command.add_flag("--strict", strict,
                   "Refuse DX8 (vs.1.1) programs that read temporary lanes nothing wrote, as DX9 vs_1_1 "
                   "programs always are (without it they are a warning and read 0)");
  CLI::Option* fragment_flag = command.add_flag(
      "--fragment", fragment,
      "The program is a piece of a shader: do not require it to write oPos (default: the program's "
      "`; vs11: fragment=yes|no` metadata line, else no)");
  command.add_flag("--no-fragment", no_fragment,
                   "Require oPos even when the program's metadata says fragment=yes")
      ->excludes(fragment_flag);
  command.add_option("--max-constants", constant_count, "Constant registers the device has (MaxVertexShaderConst)")
      ->check(CLI::Range(kDefaultConstantCount, kMaxConstantIndex + 1));
}

LoadProgramOptions ProgramFlags::ToOptions() const {
  LoadProgramOptions options;
  for (const std::string& dir : include_dirs) options.assemble.preprocess.include_dirs.emplace_back(dir);
  for (const std::string& define : defines) {
    std::size_t equals = define.find('=');
    if (equals == std::string::npos) {
      options.assemble.preprocess.defines.emplace_back(define, "1");
    } else {
      options.assemble.preprocess.defines.emplace_back(define.substr(0, equals), define.substr(equals + 1));
    }
  }
  options.assemble.validate = !skip_validation;
  options.assemble.constant_count = constant_count;
  options.assemble.require_position = !fragment;
  options.assemble.strict = strict;
  return options;
}

std::optional<bool> ProgramFlags::FragmentFlag() const {
  if (fragment) return true;
  if (no_fragment) return false;
  return std::nullopt;
}

Program LoadProgramOrFail(const std::string& path, const ProgramFlags& flags) {
  ProgramForVerify loaded = LoadProgramForVerify(path, flags.ToOptions(), flags.FragmentFlag());
  std::fputs(loaded.diagnostics.ToString().c_str(), stderr);
  if (!loaded.program) throw CommandFailure{1};
  return std::move(*loaded.program);
}

void EngineFlags::AddTo(CLI::App& command) {
  command.add_option("--engine", engine,
                     "Execution engine: " + EngineDescriptions() + "; the CPU engines give the same bits")
      ->check(CLI::IsMember(EngineSpellings()))
      ->capture_default_str();
  command.add_option("--threads", threads, "Threads for the batch and jit engines")->check(CLI::Range(1, kMaxThreadsOption))->capture_default_str();
  command.add_option("--gl-device", gl_device,
                     "EGL device for --engine gl: 'list' prints them; N picks one (default: Mesa's llvmpipe)")
      ->check([](const std::string& value) {
        return value == "list" || gl::GlDeviceIndex(value) ? std::string() : "expected 'list' or a device number";
      });
  AddChoiceOption(command, "--gl-path", gl_path, gl::kGlPathNames,
                  "How --engine gl runs the program: " + gl::kGlPathNames.Help());
  float_rules.AddTo(command);
}

std::string EngineFlags::Name() const {
  const std::optional<EngineInfo> info = FindEngine(engine);
  return info ? std::string(info->name) : engine;
}

EngineOptions EngineFlags::Options() const {
  EngineOptions options{threads};
  options.float_rules = float_rules.Rules();
  options.settings.Set(gl::GlOptions{gl::GlDeviceIndex(gl_device), gl_path});
  return options;
}

bool EngineFlags::ListGlDevicesIfAsked(const std::string& command_engines) const {
  if (!gl_device.empty() && gl_device != "list" && Name() != "gl" &&
      command_engines.find("gl") == std::string::npos) {
    std::fprintf(stderr, "warning: --gl-device applies to the gl engine only; --engine %s ignores it\n", engine.c_str());
  }
  if (gl_path != gl::GlPath::kAuto && Name() != "gl" && command_engines.find("gl") == std::string::npos) {
    std::fprintf(stderr, "warning: --gl-path applies to the gl engine only; --engine %s ignores it\n", engine.c_str());
  }
  if (gl_device != "list") return false;
  const Result<std::vector<gl::GlDeviceInfo>> devices = gl::ListGlDevices();
  if (!devices) Fail(devices.message());
  std::fputs(gl::FormatGlDeviceList(*devices).c_str(), stdout);
  return true;
}

std::unique_ptr<Engine> MakeEngineOrFail(std::string_view name, const Program& program, const ConstantBank& constants,
                                         const EngineOptions& options) {
  Result<std::unique_ptr<Engine>> engine = MakeEngine(name, program, constants, options);
  if (!engine) Fail(engine.message());
  return std::move(engine).value();
}

void NoteGlPath(const Engine& engine) {
  if (const std::optional<gl::GlPath> path = gl::GlPathOf(engine)) {
    std::fprintf(stderr, "note: --engine gl runs the %s path%s\n", std::string(gl::kGlPathNames.Name(*path)).c_str(),
                 *path == gl::GlPath::kCompute ? " (a compute shader over storage buffers)"
                                               : " (a vertex shader with transform feedback)");
  }
}

void RunOrFail(Engine& engine, const VertexArrays& inputs, VertexArrays& outputs) {
  if (const Status ran = engine.Run(inputs, outputs); !ran) Fail(ran.message());
}

void FloatRulesFlag::AddTo(CLI::App& command) {
  AddChoiceOption(command, "--float-rules", rules, kFloatRulesNames,
                  "Products of mul, mad, dp3, dp4, m*x*, dst and lit's power: " + kFloatRulesNames.Help());
}

FloatRules FloatRulesFlag::Rules() const { return rules; }

CLI::Validator SizeNumber() {
  return CLI::Validator(
      [](std::string& text) {
        std::size_t value = 0;
        auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
        if (error == std::errc() && end == text.data() + text.size()) return std::string();
        return fmt::format("'{}' is not a whole number from 0 to {}", text, std::numeric_limits<std::size_t>::max());
      },
      "");
}

void NoteRegisterOnce(std::string_view option, char letter, int index, std::vector<int>& seen) {
  if (std::find(seen.begin(), seen.end(), index) != seen.end()) {
    FailUsage(fmt::format("{} {}{} is given twice: give each register once", option, letter, index));
  }
  seen.push_back(index);
}

void Fail(const std::string& message) {
  std::fprintf(stderr, "error: %s\n", message.c_str());
  throw CommandFailure{1};
}

std::string ReadInputOrFail(const std::string& path, std::size_t max_bytes) {
  Result<std::string> input = ReadInputFile(path, max_bytes);
  if (!input) Fail(fmt::format("{}: {}", InputDisplayName(path), input.message()));
  return std::move(*input);
}

void FailUsage(const std::string& message) {
  std::fprintf(stderr, "error: %s\n", message.c_str());
  throw CommandFailure{kUsageErrorStatus};
}

void CheckInputsAndOutputs(const std::vector<std::string>& inputs, const std::vector<std::string>& outputs) {
  if (std::count(inputs.begin(), inputs.end(), kStandardInputName) > 1) {
    FailUsage("standard input ('-') can be read only once; name the other inputs as files");
  }
  const std::vector<std::filesystem::path> input_paths(inputs.begin(), inputs.end());
  for (const std::string& output : outputs) {
    if (const Status error = OutputOverwritesInput(output, input_paths); !error.ok()) FailUsage(error.message());
  }
}

}  // namespace vs11::cli
