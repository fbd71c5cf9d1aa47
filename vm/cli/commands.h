// The `vs11` subcommands. Each Add*Command registers one subcommand on the app; its callback only
// parses what CLI11 gave it and calls the library. Exit codes: 0 success, 1 the input is wrong (or a
// verification failed), 2 usage errors (CLI11's own).
#pragma once

#include <CLI/CLI.hpp>

namespace vs11::cli {

// Thrown from a subcommand callback to end with a message and a status (caught in main).
struct CommandFailure {
  int exit_code = 1;
};

void AddAsmCommand(CLI::App& app);
void AddDisasmCommand(CLI::App& app);
void AddValidateCommand(CLI::App& app);
void AddRunCommand(CLI::App& app);
void AddCountCommand(CLI::App& app);
void AddVerifyCommand(CLI::App& app);
void AddTranslateCommand(CLI::App& app);

}  // namespace vs11::cli
