#include "irradiance/cli/subcommands.h"

namespace vs11::irradiance::cli {

void AddSubcommands(CLI::App& app) {
  // `irrmap chart` and `irrmap stability` register here, one Add...Command(app) line each.
  AddChartCommand(app);
  AddStabilityCommand(app);
  AddBatchCommand(app);
  AddBatchMergeCommand(app);
}

}  // namespace vs11::irradiance::cli
