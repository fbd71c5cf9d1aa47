// `irrmap chart`: the speed/accuracy sweep (irradiance/report/speed_accuracy.h) written as a CSV and a
// gnuplot chart.
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "irradiance/cli/subcommands.h"
#include "vm/cli/choice_option.h"
#include "irradiance/jobs/irrmap_job.h"
#include "irradiance/report/speed_accuracy.h"

namespace vs11::irradiance::cli {
namespace {

struct ChartArguments {
  SpeedAccuracyOptions options;
  std::string out_dir = "out";
};

void RunChart(const ChartArguments& arguments) {
  if (const Status usage = CheckSpeedAccuracyOptions(arguments.options); !usage.ok()) {
    throw CLI::ValidationError(usage.message());
  }
  if (const Status error = CheckOutputFolder(arguments.out_dir); !error.ok()) throw SubcommandFailure(error.message());
  SpeedAccuracyResult result;
  const auto progress = [](std::string_view environment, int index, int count) {
    fmt::print(stderr, "irrmap chart: {} ({} of {})\n", environment, index + 1, count);
  };
  if (const Status error = RunSpeedAccuracySweep(arguments.options, result, progress); !error.ok()) {
    throw SubcommandFailure(error.message());
  }
  for (const std::string& warning : result.warnings) fmt::print(stderr, "irrmap: warning: {}\n", warning);
  std::vector<std::filesystem::path> written;
  if (const Status error = WriteSpeedAccuracy(result, arguments.out_dir, written); !error.ok()) {
    throw SubcommandFailure(error.message());
  }
  fmt::print("{:<12} {:<6} {:>5} {:>9} {:>11} {:>9} {:>13} {:>12} {:>10} {:>10}\n", "environment", "method", "level",
             "size", "update ms", "mips ms", "mean rel err", "max rel err", "peak err", "rms err");
  for (const SpeedAccuracyPoint& point : result.points) {
    double mips_ms = 0.0;
    for (const SpeedAccuracyEnvironment& environment : result.environments) {
      if (environment.name == point.environment) mips_ms = environment.mips_ms;
    }
    fmt::print("{:<12} {:<6} {:>5} {:>9} {:>11.4f} {:>9.3f} {:>11.3f} % {:>10.3f} % {:>8.3f} % {:>8.3f} %\n",
               point.environment, kProjectionMethodNames.Name(point.method), point.level,
               fmt::format("{0}x{0}", point.size), point.update_ms, mips_ms, 100.0 * point.error.mean_relative,
               100.0 * point.error.max_relative, 100.0 * point.error.max_peak, 100.0 * point.error.max_rms);
  }
  fmt::print("wrote:");
  for (const auto& path : written) fmt::print(" {}", path.string());
  fmt::print("\n");
}

}  // namespace

void AddChartCommand(CLI::App& app) {
  auto arguments = std::make_shared<ChartArguments>();
  CLI::App* chart = app.add_subcommand(
      "chart",
      "Speed against accuracy: every mip level x each projection method x the environments; writes\n"
      "speed_accuracy.csv, speed_accuracy.svg and speed_accuracy.png into --out.");
  chart->footer(
      "Methods, both from mip level k of the environment (faces halved k times):\n"
      "  mip     the paper's: level k's mean radiance times the basis pyramid (each weight summed over the\n"
      "          full-resolution texels it covers)\n"
      "  direct  the basis evaluated at level k's texel centres, as if level k were the environment; at\n"
      "          level 0 the plain full-resolution projection\n"
      "Time per update: one projection (mips built beforehand; their time is the mips_ms column), the\n"
      "median of --batches batch means, each batch repeating it for --min-batch-ms.\n"
      "Error: of the paper's program's irradiance against brute-force integration at --error-normals\n"
      "normals, the same figures as irrmap's level table and coeffs.json for the same level: mean and max\n"
      "relative, peak (max |E - E*| / max E*) and rms (RMS of E - E* / mean E*), each the worst of r, g, b.\n"
      "The chart plots time (log x) against the --error-metric figure (log y; relative: the mean), one\n"
      "colour per environment (named by the file's base name), solid for mip and dashed for direct, each\n"
      "point labelled by its level. gnuplot draws it.\n"
      "Exit status: 0 success, 1 an environment or an output failed, 2 a usage error (an unknown option,\n"
      "a bad option value; before any work).\n"
      "\n"
      "Examples:\n"
      "  irrmap chart                          # every built-in at 256x256, into out/\n"
      "  irrmap chart sky spot --face-size 64 --error-metric rms --out chart-64\n"
      "  irrmap chart probe.hdr --layout angular --face-size 256\n");
  chart->add_option("ENV", arguments->options.environments,
                    "environments (files, {face} patterns or built-in names); default: every built-in");
  chart->add_option("--out", arguments->out_dir, "output directory")->capture_default_str();
  vs11::cli::AddChoiceOption(*chart, "--layout", arguments->options.layout, kLayoutNames,
                              "layout of files (as irrmap's --layout)");
  chart->add_option("--face-size", arguments->options.face_size,
                    "face size of built-ins and of cubes resampled from latlong/angular maps (a power of two)")
      ->capture_default_str();
  chart->add_option("--error-normals", arguments->options.error_normals, "normals the error is measured at")
      ->capture_default_str();
  vs11::cli::AddChoiceOption(*chart, "--error-metric", arguments->options.error_metric, kErrorMetricNames,
                              fmt::format("the error on the chart's axis: {} (relative: its mean)",
                                          kErrorMetricNames.List()));
  chart->add_option("--threads", arguments->options.threads,
                    "threads of the ground truth and the vertex program (0 = every core); the timed "
                    "projections run on one")
      ->capture_default_str();
  chart->add_option("--batches", arguments->options.batches, "timing batches per point (the median is kept)")
      ->capture_default_str();
  chart->add_option("--min-batch-ms", arguments->options.min_batch_ms, "minimum length of a timing batch")
      ->capture_default_str();
  chart->callback([arguments] { RunChart(*arguments); });
}

}  // namespace vs11::irradiance::cli
