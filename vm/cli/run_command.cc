// vs11 run: the program over vertices from CSV files or over a sphere of normals.
#include <charconv>
#include <cstdio>
#include <filesystem>
#include <memory>

#include <fmt/format.h>

#include "vm/cli/cli_support.h"
#include "vm/cli/commands.h"
#include "vm/cli/streamed_output.h"
#include "vm/cli/texture_flags.h"
#include "vm/cli/trace_output.h"
#include "vm/cli/vertex_sources.h"
#include "vm/core/atomic_file.h"
#include "vm/core/input_file.h"
#include "vm/engines/engine_factory.h"
#include "vm/io/vertex_io.h"
#include "vm/reference/sphere_normals.h"

namespace vs11::cli {
namespace {

// "v1" -> 1
int InputRegisterFromName(const std::string& name) {
  const Result<InputSpec> spec = ParseInputSpec(name + "=");
  if (!spec) FailUsage("--sphere-reg " + spec.message());
  return spec->reg;
}

int DeclaredNormalRegister(const Program& program) {
  for (const Instruction& instruction : program.instructions) {
    if (instruction.opcode == Opcode::kDcl && instruction.usage == kDeclUsageNormal) return instruction.dest.reg.index;
  }
  return -1;
}

ConstantBank LoadConstants(const std::vector<std::string>& files, const std::vector<std::string>& assignments,
                           int count, AssignedConstants& assigned) {
  ConstantBank bank(count);
  for (const std::string& file : files) {
    const std::string text = ReadInputOrFail(file, kMaxConstantsFileBytes);
    Diagnostics diagnostics;
    ParseConstantsText(text, InputDisplayName(file), bank, diagnostics, &assigned);
    std::fputs(diagnostics.ToString().c_str(), stderr);
    if (diagnostics.HasErrors()) throw CommandFailure{1};
  }
  // Each register once across the flags (a second value would silently win), then after the files'.
  AssignedConstants flagged;
  std::vector<int> once_c, once_i, once_b;
  auto note_new = [](char letter, const std::vector<int>& list, std::size_t from, std::vector<int>& once) {
    for (std::size_t i = from; i < list.size(); ++i) NoteRegisterOnce("--const", letter, list[i], once);
  };
  for (const std::string& assignment : assignments) {
    const AssignedConstants before = flagged;
    if (const Status parsed = ParseConstantAssignment(assignment, bank, &flagged); !parsed) {
      FailUsage("--const: " + parsed.message());
    }
    note_new('c', flagged.floats, before.floats.size(), once_c);
    note_new('i', flagged.integers, before.integers.size(), once_i);
    note_new('b', flagged.booleans, before.booleans.size(), once_b);
  }
  auto append = [](std::vector<int>& to, const std::vector<int>& from) { to.insert(to.end(), from.begin(), from.end()); };
  append(assigned.floats, flagged.floats);
  append(assigned.integers, flagged.integers);
  append(assigned.booleans, flagged.booleans);
  return bank;
}

struct RunArgs {
  std::string program, out, sphere_register;
  std::string missing = "error";  // --missing: "error" or "zeros"
  std::vector<std::string> consts_files, const_flags, input_flags;
  int sphere = 0;
  ProgramFlags flags;
  EngineFlags engine;
  TraceFlags trace;
  VertexSourceFlags sources;
  TextureFlags textures;
};

using SuppliedInputs = mesh::RegisterData;  // register, one row per vertex

// --input v#=FILE.csv[:COLUMNS], each file read and parsed, its problems printed.
SuppliedInputs ReadCsvInputs(const std::vector<std::string>& input_flags) {
  SuppliedInputs supplied;
  std::vector<int> given;
  for (const std::string& flag : input_flags) {
    const Result<InputSpec> spec = ParseInputSpec(flag);
    if (!spec) FailUsage("--input " + spec.message());
    NoteRegisterOnce("--input", 'v', spec->reg, given);
  }
  for (const std::string& flag : input_flags) {
    const InputSpec spec = ParseInputSpec(flag).value();  // checked in the loop above
    const std::string text = ReadInputOrFail(spec.file, kMaxVertexCsvBytes);
    Diagnostics diagnostics;
    std::vector<Vec4f> rows = ParseVertexCsv(text, InputDisplayName(spec.file), diagnostics, spec.columns);
    std::fputs(diagnostics.ToString().c_str(), stderr);
    if (diagnostics.HasErrors()) throw CommandFailure{1};
    supplied.emplace_back(spec.reg, std::move(rows));
  }
  return supplied;
}

// --sphere N: the normals go into the dcl_normal register (or --sphere-reg), and become the first
// columns of the output CSV (`prefix`).
void AddSphereInput(const RunArgs& args, const Program& program, SuppliedInputs& supplied, CsvColumns& prefix) {
  int reg = args.sphere_register.empty() ? DeclaredNormalRegister(program)
                                         : InputRegisterFromName(args.sphere_register);
  if (reg < 0) Fail("--sphere: the program declares no dcl_normal register; name one with --sphere-reg");
  std::vector<Vec4f> rows;
  for (const glm::dvec3& n : SphereNormals(args.sphere)) {
    rows.push_back({static_cast<float>(n.x), static_cast<float>(n.y), static_cast<float>(n.z), 1.0f});
    prefix.values.insert(prefix.values.end(), rows.back().begin(), rows.back().begin() + 3);
  }
  std::string name = fmt::format("v{}", reg);
  prefix.header = {name + ".x", name + ".y", name + ".z"};
  supplied.emplace_back(reg, std::move(rows));
}

// Every supplied register must hold the same number of vertices; returns it.
std::size_t CommonVertexCount(const SuppliedInputs& supplied) {
  if (supplied.empty()) Fail("no vertices: give --input v#=FILE.csv, --sphere N, --mesh, --npy or --buffer");
  std::size_t count = supplied.front().second.size();
  for (const auto& [reg, rows] : supplied) {
    if (rows.size() != count) {
      Fail(fmt::format("v{} has {} vertices but v{} has {}", reg, rows.size(), supplied.front().first, count));
    }
  }
  return count;
}

VertexArrays FillInputArrays(const SuppliedInputs& supplied, std::size_t count, const std::vector<int>& registers) {
  VertexArrays inputs = MakeInputArrays(count, registers);
  for (const auto& [reg, rows] : supplied) {
    for (std::size_t i = 0; i < count; ++i) {
      for (int c = 0; c < 4; ++c) inputs.lane(reg, c)[i] = rows[i][c];
    }
  }
  return inputs;
}

// The files `vs11 run` reads and writes, for CheckInputsAndOutputs.
std::vector<std::string> RunInputFiles(const RunArgs& args) {
  std::vector<std::string> files = {args.program, args.sources.mesh, args.sources.buffer};
  files.insert(files.end(), args.consts_files.begin(), args.consts_files.end());
  for (const std::string& flag : args.input_flags) {
    if (const Result<InputSpec> spec = ParseInputSpec(flag)) files.push_back(spec->file);
  }
  for (const std::string& flag : args.sources.npy_inputs) files.push_back(flag.substr(flag.find('=') + 1));
  for (const std::string& file : args.textures.Files()) files.push_back(file);
  std::erase(files, std::string());
  return files;
}

std::vector<std::string> RunOutputFiles(const RunArgs& args) {
  std::vector<std::string> files = {args.out, args.sources.out_buffer, args.sources.out_mesh, args.trace.json_file};
  if (!args.sources.out_npy_dir.empty()) {  // every name --out-npy may write, before the program says which
    for (int slot = 0; slot < kOutputSlotCount; ++slot) {
      files.push_back((std::filesystem::path(args.sources.out_npy_dir) / (OutputSlotName(slot) + ".npy")).string());
    }
  }
  return files;
}

void RunProgram(const RunArgs& args) {
  if (args.engine.ListGlDevicesIfAsked("")) return;
  CheckInputsAndOutputs(RunInputFiles(args), RunOutputFiles(args));
  Program program = LoadProgramOrFail(args.program, args.flags);
  AssignedConstants constants_set;
  ConstantBank constants = LoadConstants(args.consts_files, args.const_flags, args.flags.constant_count, constants_set);
  BindTextures(args.textures, program, args.program, constants);
  SuppliedInputs supplied = ReadCsvInputs(args.input_flags);
  CsvColumns prefix;
  if (args.sphere > 0) AddSphereInput(args, program, supplied, prefix);
  VertexSources sources = CollectVertexSources(args.sources, program, constants, supplied);
  const std::size_t count = CommonVertexCount(supplied);
  std::vector<int> registers;
  for (const auto& entry : supplied) registers.push_back(entry.first);
  const UnsetRegisters unset = FindUnsetRegisters(program, constants_set, registers);
  if (args.missing == "error") {
    const Status set = CheckNoUnsetRegisters(
        unset, registers,
        {"a def, --consts nor --const", "--input, --sphere, --mesh, --npy or --buffer", "--missing zeros"});
    if (!set) FailUsage(fmt::format("{}: {}", args.program, set.message()));
  }
  for (const std::string& warning : UnsetRegisterWarnings(unset)) {
    std::fprintf(stderr, "%s: warning: %s\n", args.program.c_str(), warning.c_str());
  }
  VertexArrays inputs = FillInputArrays(supplied, count, registers);
  VertexArrays outputs = MakeOutputArrays(count, program);
  const std::unique_ptr<Engine> engine = MakeEngineOrFail(args.engine.Name(), program, constants, args.engine.Options());
  NoteGlPath(*engine);
  RunOrFail(*engine, inputs, outputs);
  if (args.trace.active()) {
    ReportTraces(args.trace, args.program, program, constants, inputs, outputs, args.engine.Name(),
                 args.engine.float_rules.Rules());
  }
  WriteVertexOutputs(args.sources, sources, program, outputs);
  if (args.out.empty() && (args.sources.WritesOutputFiles() || args.trace.active())) return;
  auto write_csv = [&](const ByteSink& sink) { WriteOutputCsv(program, outputs, prefix, sink); };
  if (args.out.empty()) {
    write_csv(StdoutSink());
    if (std::fflush(stdout) != 0) Fail("cannot write to standard output");
  } else if (const Status written = WriteStreamedAtomically(args.out, write_csv); !written) {
    Fail(written.message());
  }
}

constexpr const char* kRunFooter =
    "Constants: def lines in the program win over --const flags, which win over --consts files (a\n"
    "warning names every register a def overrides). The later models' integer and boolean constants\n"
    "are set the same ways: --const i0=3,0,1,0 --const b2=true, or defi/defb and `i0 = 3 0 1 0` lines\n"
    "in a --consts file; an i# is x the rep or loop count 0-255, y aL's first value 0-255, z aL's step\n"
    "-128-127, w 0 (D3D9's loop), and a value outside is an error. A constant the program reads that\n"
    "nobody sets, or an input register it reads that nothing supplies, is an error naming it (exit 2);\n"
    "--missing zeros runs anyway with a warning, constants reading 0, 0, 0, 0 (i# 0: no iteration; b#\n"
    "false) and inputs 0, 0, 0, 1.\n"
    "Inputs: --input v1=FILE.csv (a vertex a row, 1-4 numbers separated by ',' or blanks, or by ';';\n"
    "inf, -inf and nan are numbers; missing components read 0,0,0,1; a first row of names is a\n"
    "header), or columns by header name: --input v0=out.csv:oPos reads oPos.x..oPos.w into their\n"
    "lanes, --input v0=out.csv:oD0.x,oD0.y,oD0.z fills x, y, z in that order; so the CSV this\n"
    "command writes reads back. Or\n"
    "--sphere N: N unit normals spread evenly over the sphere, written into the register the program\n"
    "declares with dcl_normal, or the one named by --sphere-reg.\n"
    "Outputs: CSV with a header naming each written output lane (raw values: the clamping D3D applies\n"
    "to oD0/oD1/oFog after the shader is not applied).\n"
    "Debugging: --trace 0,5 prints vertices 0 and 5 instruction by instruction (source line, values\n"
    "read, lanes written; a later model's as its flow control runs them, with what each flow instruction\n"
    "decided) on the reference engine, beside the --engine's outputs, which must be identical\n"
    "(exit 1 if not); the CSV then goes only to --out. --trace-json FILE writes the same record as JSON.\n"
    "--engine gl runs the program's GLSL ES translation (vs11 translate) on an OpenGL ES driver through\n"
    "EGL with no display: Mesa's llvmpipe, or the EGL device --gl-device N names (--gl-device list\n"
    "prints them); as a compute shader where the context offers OpenGL ES 3.1, else through transform\n"
    "feedback (--gl-path compute|transform-feedback forces one; a note on stderr says which ran).\n"
    "Where no EGL device gives OpenGL ES 3.0 it says why and exits 1. Its outputs equal the\n"
    "other engines' on ordinary inputs; a driver may flush denormals and lose -0 (README, \"The gl engine\").\n\n"
    "Float rules: --float-rules legacy makes every product of mul, mad, dp3, dp4, m*x*, dst and lit's\n"
    "power 0 when an operand is 0 (0 * inf = 0, as DX8-era hardware), on every engine and in --trace;\n"
    "d3d9 (the default) keeps IEEE's NaN.\n\n"
    "Vertex textures (vs_3_0's texldl; engines ref, batch and jit): --texture s0=FILE.npy binds a float32\n"
    "array of shape (H, W) as R32F (samples (r, 1, 1, 1)) or (H, W, 4) as A32B32G32R32F to a sampler the\n"
    "program declares with dcl_2d; one level, point sampling: texel floor(u * W), floor(v * H), row 0 at\n"
    "v = 0.\n"
    "--texture-address s0=clamp (or s0=wrap,clamp for u and v) sets the address modes: wrap (the\n"
    "default), clamp or border (0 outside [0, 1)). A declared sampler with no texture reads (0, 0, 0, 1),\n"
    "with a warning.\n\n"
    "Examples:\n"
    "  vs11 run programs/sh9_irradiance.vsh --fragment --consts out/constants.vsh --sphere 6 --sphere-reg v0\n"
    "  vs11 run programs/sh9_irradiance.vsh --fragment --consts out/constants.vsh --sphere 6 --sphere-reg v0 --trace 2\n"
    "  vs11 run light.vsh --input v0=positions.csv --input v1=normals.csv --const c4=0,0,1,0 --out lit.csv\n"
    "  vs11 run light.vsh --input v0=lit.csv:oPos --input v1=normals.csv --const c4=0,0,1,0\n"
    "  vs11 run programs/sh9_irradiance.vsh --fragment --consts out/constants.vsh --sphere 6 --sphere-reg v0 --engine gl\n"
    "  vs11 run programs/sh9_irradiance.vsh --fragment --consts out/constants.vsh --sphere 6 --sphere-reg v0 --engine gl --gl-path transform-feedback\n"
    "  vs11 run heights.vsh --input v0=positions.csv --texture s0=heights.npy --texture-address s0=clamp\n"
    "  vs11 run programs/sh9_irradiance.vsh --gl-device list\n"
    "  vs11 run programs/sh9_irradiance.vsh --input v0=infinite_normals.csv --missing zeros --float-rules legacy";

}  // namespace

void AddRunCommand(CLI::App& app) {
  auto args = std::make_shared<RunArgs>();
  CLI::App* command = app.add_subcommand("run", "Run a program (vs_1_1, vs_2_0, vs_2_x, vs_3_0) over vertices and print its outputs as CSV");
  command->footer(kRunFooter);
  command->add_option("program", args->program, "Program (.vsh or .vso; - reads standard input, once per command line)")->required();
  command->add_option("--const", args->const_flags, "Constant register value, e.g. c4=1,0,0,1; i0=3,0,1,0 or b2=true for the later models");
  command->add_option("--consts", args->consts_files, "File of `def c#, x, y, z, w` or `c# = x y z w` lines, defi/defb or `i# = ...`, `b# = true` for the later models (- reads standard input)");
  command->add_option("--input", args->input_flags,
                      "Input register from a CSV file, e.g. v1=normals.csv or v0=out.csv:oPos (columns by name); v1=- reads standard input");
  command->add_option("--sphere", args->sphere, "Run over N unit normals spread over the sphere")->check(CLI::Range(1, 100000000));
  command->add_option("--sphere-reg", args->sphere_register, "Input register for --sphere normals (default: dcl_normal)");
  command->add_option("--out", args->out, "Write the CSV here (atomically) instead of stdout");
  command->add_option("--missing", args->missing,
                      "error: a constant or input the program reads that nothing sets stops the run; zeros: they "
                      "read 0 (inputs 0, 0, 0, 1), with a warning")
      ->check(CLI::IsMember({"error", "zeros"}))
      ->capture_default_str();
  args->flags.AddTo(*command);
  args->engine.AddTo(*command);
  args->trace.AddTo(*command);
  args->sources.AddTo(*command);
  args->textures.AddTo(*command);
  command->callback([args] { RunProgram(*args); });
}

}  // namespace vs11::cli
