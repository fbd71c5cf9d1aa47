// Helpers the vs11 subcommands share: loading a program with diagnostics printed, engine names,
// preprocessor flags.
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "vm/machine.h"
#include "vm/program_file.h"

namespace vs11::cli {

// -I and -D and --skip-validation and --constants, bound to one LoadProgramOptions.
struct ProgramFlags {
  std::vector<std::string> include_dirs;
  std::vector<std::string> defines;
  bool skip_validation = false;
  bool fragment = false;
  int constant_count = kDefaultConstantCount;

  void AddTo(CLI::App& command, bool offer_skip_validation = true);
  LoadProgramOptions ToOptions() const;
};

// Loads and (unless skipped) validates; prints every diagnostic to stderr; throws CommandFailure{1}
// when there are errors.
Program LoadProgramOrFail(const std::string& path, const ProgramFlags& flags);

// "--engine ref|batch|jit" (jit by default: batch kernels where the CPU has no AVX2) and "--threads N".
struct EngineFlags {
  std::string engine = "jit";
  int threads = 1;
  void AddTo(CLI::App& command);
  EngineKind Kind() const;
  EngineOptions Options() const { return {threads}; }
};

// Prints "error: MESSAGE" to stderr and throws CommandFailure{1}.
[[noreturn]] void Fail(const std::string& message);

}  // namespace vs11::cli
