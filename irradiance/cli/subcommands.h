// irrmap's subcommands beside the default job (`irrmap [ENV] ...`). Each one registers itself on
// the app with its own options and does its work in its CLI11 callback; a failure throws
// SubcommandFailure, which main prints as "irrmap: error: ..." with exit status 1, and a bad option
// value, checked before any work, throws CLI::ValidationError: a usage error, exit status 2, as
// CLI11's own.
#pragma once

#include <stdexcept>

#include <CLI/CLI.hpp>

namespace vs11::irradiance::cli {

struct SubcommandFailure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Registers every subcommand (subcommands.cc); a new one adds its line there.
void AddSubcommands(CLI::App& app);

void AddChartCommand(CLI::App& app);  // irrmap chart (chart_command.cc)
void AddStabilityCommand(CLI::App& app);  // stability_command.cc
void AddBatchCommand(CLI::App& app);      // irrmap batch (batch_command.cc)
void AddBatchMergeCommand(CLI::App& app);  // irrmap batch-merge (batch_merge_command.cc)

}  // namespace vs11::irradiance::cli
