// `irrmap stability`: parses its options and calls RunStability / WriteStabilityReport
// (irradiance/report/stability_report.h), which do all the work.
#include <unistd.h>

#include <cstdio>
#include <memory>
#include <string>

#include <fmt/format.h>

#include "irradiance/cli/subcommands.h"
#include "vm/cli/choice_option.h"
#include "irradiance/jobs/irrmap_job.h"
#include "irradiance/report/stability_report.h"

namespace vs11::irradiance::cli {
namespace {

constexpr int kProgressBarWidth = 30;

// A progress bar on stderr, only when stderr is a terminal.
StabilityProgress TerminalProgress() {
  if (!isatty(fileno(stderr))) return {};
  return [last = std::string(), last_percent = -1](std::string_view stage, double fraction) mutable {
    const int percent = static_cast<int>(fraction * 100.0);
    if (percent == last_percent && stage == last) return;
    last_percent = percent;
    last = std::string(stage);
    const int filled = static_cast<int>(fraction * kProgressBarWidth + 0.5);
    fmt::print(stderr, "\rirrmap stability: {:<12} [{}{}] {:3}%", stage, std::string(filled, '#'),
               std::string(kProgressBarWidth - filled, ' '), percent);
    if (fraction >= 1.0) fmt::print(stderr, "\n");
    std::fflush(stderr);
  };
}

}  // namespace

void AddStabilityCommand(CLI::App& app) {
  auto options = std::make_shared<StabilityOptions>();
  auto out_dir = std::make_shared<std::string>(options->out_dir.string());
  CLI::App* command = app.add_subcommand(
      "stability",
      "Where the nine-coefficient method fails, measured: a light swept from 90 to 0.25 degrees at constant power "
      "(ringing, and the windows and the non-negative fit against it, also on the built-ins and lat-long probes), "
      "the error each mip level adds for every built-in environment, the --max-error level pick and the "
      "(program, level) pick with its hit rate, and precision (float sums, non-unit and zero normals, denormal constants, HDR "
      "radiance). Writes DIR/stability.md with the charts sweep.png, ringing.png and levels.png (gnuplot) beside "
      "it. About a minute at the defaults on two cores; a progress bar is shown when stderr is a terminal.");
  // Its own footer: CLI11 copies the parent's, which describes the main job's outputs.
  command->footer(
      "Outputs (in --out DIR, created if needed; each file written to a temporary and renamed):\n"
      "  stability.md    the findings with their tables, embedding the three charts\n"
      "  sweep.png       max and mean error against the light's radius, per window\n"
      "  ringing.png     lowest irradiance over the sphere against the light's radius, per window\n"
      "  levels.png      error of each mip level against level 0, per environment\n"
      "Exit status: 0 success, 1 an output failed, 2 a usage error (an unknown option, a bad option value;\n"
      "before any work).\n"
      "\n"
      "Examples:\n"
      "  irrmap stability --out irradiance/images/stability   # the report the README links to");
  command->add_option("--out", *out_dir, "output directory")->capture_default_str();
  command->add_option("--face-size", options->face_size, "face size of the sweep's and the level study's maps")
      ->capture_default_str();
  command->add_option("--precision-face-size", options->precision_face_size,
                      "face size of the float-against-double accumulation test")
      ->capture_default_str();
  command->add_option("--error-normals", options->error_normals, "normals (evenly spread) of every comparison")
      ->capture_default_str();
  command->add_option("--max-error", options->max_error, fmt::format("target of the level pick (a fraction: {} = {} %)",
                                                                     kDefaultMaxLevelError, 100 * kDefaultMaxLevelError))
      ->capture_default_str();
  vs11::cli::AddChoiceOption(*command, "--error-metric", options->error_metric, kErrorMetricNames,
                              fmt::format("what --max-error bounds, as irrmap's: {}", kErrorMetricNames.List()));
  command->add_option("--threads", options->threads, "worker threads (0 = every core)")->capture_default_str();
  command->callback([options, out_dir] {
    options->out_dir = *out_dir;
    if (const Status usage = CheckStabilityOptions(*options); !usage.ok()) throw CLI::ValidationError(usage.message());
    if (const Status error = CheckOutputFolder(options->out_dir); !error.ok()) throw SubcommandFailure(error.message());
    StabilityReport report;
    if (const Status error = RunStability(*options, report, TerminalProgress()); !error.ok()) {
      throw SubcommandFailure(error.message());
    }
    std::vector<std::filesystem::path> written;
    if (const Status error = WriteStabilityReport(report, written); !error.ok()) {
      throw SubcommandFailure(error.message());
    }
    fmt::print("wrote:");
    for (const auto& path : written) fmt::print(" {}", path.string());
    fmt::print("\n");
  });
}

}  // namespace vs11::irradiance::cli
