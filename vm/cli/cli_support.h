// Helpers the vs11 subcommands share: loading a program with diagnostics printed, engine names,
// preprocessor flags.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>

#include "vm/asm/program_file.h"
#include "vm/core/float_rules.h"
#include "vm/core/machine.h"
#include "vm/gl/gl_engine.h"

namespace vs11::cli {

// -I, -D, --skip-validation, --strict, --fragment/--no-fragment and --max-constants, bound to one
// LoadProgramOptions.
struct ProgramFlags {
  std::vector<std::string> include_dirs;
  std::vector<std::string> defines;
  bool skip_validation = false;
  bool fragment = false;
  bool no_fragment = false;
  bool strict = false;
  int constant_count = kDefaultConstantCount;

  void AddTo(CLI::App& command, bool offer_skip_validation = true);
  LoadProgramOptions ToOptions() const;
  // --fragment or --no-fragment when one was given; otherwise the program's `; vs11: fragment=`
  // metadata decides.
  std::optional<bool> FragmentFlag() const;
};

// Loads and (unless skipped) validates, honouring the program's `; vs11: fragment=yes` metadata
// unless a flag says otherwise; prints every diagnostic to stderr; throws CommandFailure{1} when
// there are errors.
Program LoadProgramOrFail(const std::string& path, const ProgramFlags& flags);

// "--float-rules d3d9|legacy" (vm/core/float_rules.h): for the engines and the translation.
struct FloatRulesFlag {
  FloatRules rules = FloatRules::kD3d9;
  void AddTo(CLI::App& command);
  FloatRules Rules() const;
};

// "--engine NAME" (a registered engine, vm/engines/engine_factory.h; jit by default), "--threads N",
// "--gl-device list|N", "--gl-path auto|compute|transform-feedback" and "--float-rules".
struct EngineFlags {
  std::string engine = "jit";
  int threads = 1;
  std::string gl_device;  // empty (llvmpipe), "list" or an EGL device's index
  gl::GlPath gl_path = gl::GlPath::kAuto;
  FloatRulesFlag float_rules;
  void AddTo(CLI::App& command);
  std::string Name() const;  // the registered name ("ref" for "reference")
  EngineOptions Options() const;
  // With --gl-device list: prints the EGL devices and returns true (the command is done: exit 0, or
  // CommandFailure{1} where EGL lists none). Warns when --gl-device is given to another engine.
  bool ListGlDevicesIfAsked(const std::string& command_engines) const;
};

// MakeEngine (vm/engines/engine_factory.h), or the engine's error printed and CommandFailure{1} where
// it cannot be had (the gl engine without a device).
std::unique_ptr<Engine> MakeEngineOrFail(std::string_view name, const Program& program, const ConstantBank& constants,
                                         const EngineOptions& options);

// For a gl engine, "note: --engine gl runs the compute path (...)" or the transform-feedback one, on
// stderr; nothing for the other engines.
void NoteGlPath(const Engine& engine);

// Runs `engine`; prints its error and throws CommandFailure{1} when the run failed (a driver's error).
void RunOrFail(Engine& engine, const VertexArrays& inputs, VertexArrays& outputs);

// A CLI11 check for an option read into a std::size_t (--stride, --trace): a decimal number that fits
// it, so that -1 or 2^64 is a usage error rather than 2^64 - 1.
CLI::Validator SizeNumber();

// A usage error when a repeatable option (--input, --npy, --element, --const) names the register
// `letter``index` a second time, which would otherwise silently keep one of the values; else notes it.
void NoteRegisterOnce(std::string_view option, char letter, int index, std::vector<int>& seen);

// Prints "error: MESSAGE" to stderr and throws CommandFailure{1}.
[[noreturn]] void Fail(const std::string& message);
// The same for a flag's value that no input can make right (exit 2, as CLI11's own usage errors).
[[noreturn]] void FailUsage(const std::string& message);

// The whole of an input file named on the command line ("-": standard input), read once and at most
// `max_bytes` (vm/core/input_file.h); or Fail with "NAME: why".
std::string ReadInputOrFail(const std::string& path, std::size_t max_bytes);

// Before any work: a usage error (exit 2) when two inputs are "-" (standard input can be read only
// once) or when one of `outputs` is the same file as one of `inputs`, which it would overwrite.
void CheckInputsAndOutputs(const std::vector<std::string>& inputs, const std::vector<std::string>& outputs);

}  // namespace vs11::cli
