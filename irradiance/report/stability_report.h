// The stability report of `irrmap stability --out DIR`: runs every measurement of stability.h at
// report sizes (with the non-negative fit and the order choice, stability_orders.cc) and writes
// DIR/stability.md (tables and findings) with the charts it embeds,
// DIR/sweep.png (error against light size per window), DIR/ringing.png (lowest irradiance against
// light size) and DIR/levels.png (error of each mip level per environment), drawn by gnuplot.
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "irradiance/io/environment_io.h"
#include "irradiance/report/stability.h"
#include "irradiance/sh/level_choice.h"
#include "vm/core/result.h"

namespace vs11::irradiance {

struct StabilityOptions {
  int face_size = kDefaultFaceSize;  // the sweep's and the level study's cube maps (a power of two)
  int precision_face_size = 2048;  // float against double accumulation (a power of two)
  int error_normals = 1000;       // SphereNormals for every comparison
  double max_error = kDefaultMaxLevelError;  // the level pick's target
  ErrorMetric error_metric = kDefaultErrorMetric;  // what max_error bounds (irrmap's --error-metric)
  // Light radii of the sweep, largest first; the spot's power stays that of SpotParams.
  std::vector<double> radii = {90, 80, 70, 60, 45, 30, 20, 15, 10, 7, 5, 3, 2, 1.5, 1, 0.5, 0.25};
  int threads = 0;  // 0: every core
  std::filesystem::path out_dir = "stability";
};

struct StabilityReport {
  StabilityOptions options;
  int threads = 1;
  std::vector<WindowVariant> variants;  // of the sweep
  std::vector<SpotSweepRow> sweep;
  double widths_radius_degrees = 2.0;          // the spot of the window-width table
  std::vector<WindowedError> widths_spot;      // hanning and lanczos of several widths
  std::vector<WindowedError> widths_sky;
  std::vector<LevelStudy> levels;              // every built-in, then spots of other sizes
  double placement_radius_degrees = 1.0;
  std::vector<SpotPlacementRow> placement;
  std::vector<AccumulationPrecision> accumulation;  // sky, HDR sky
  ProgramPrecision programs;
  std::vector<ScaledRun> scaled;
  std::vector<HdrResult> hdr;
  ZeroEnvironmentResult zero;
  // Every window and the non-negative fit on the built-ins and on lat-long probes (stability_orders.cc),
  // and the fit's time per environment change (median of kFitTimingRuns, ms) for each of them.
  struct WindowCase {
    std::string environment;
    std::vector<WindowedError> windows;  // ReportWindowVariants() order
    double fit_ms = 0.0;
  };
  std::vector<WindowCase> window_cases;
  std::vector<std::pair<std::string, double>> seconds;  // time per section
};

using StabilityProgress = std::function<void(std::string_view stage, double fraction)>;

// What is wrong with the options themselves (a bad value: a usage error; kOptionValue or
// kFaceSize), or success.
Status CheckStabilityOptions(const StabilityOptions& options);

// Runs every measurement. Success, or the error that says what went wrong (bad option, program
// load).
Status RunStability(const StabilityOptions& options, StabilityReport& report, const StabilityProgress& progress = {});

// "1.23 %", "3.1e-04 %", "inf": a fraction as the report prints it.
std::string ReportPercent(double fraction);

// Sections of the markdown written in irradiance/report/stability_orders.cc: the non-negative fit against
// the windows on the sweep, and the (program, level) choice on the level study's environments.
std::string NonNegativeSection(const StabilityReport& report);
void RunWindowCases(StabilityReport& report, std::span<const glm::dvec3> normals);
std::string OrderChoiceSection(const StabilityReport& report);

// The markdown of the report; charts are referenced by their file names beside it.
std::string FormatStabilityMarkdown(const StabilityReport& report);

// Renders the charts and writes the markdown into report.options.out_dir (created if needed), each
// file atomically; on failure the files already written by this call are removed. Returns the
// paths written, or the error.
Status WriteStabilityReport(const StabilityReport& report, std::vector<std::filesystem::path>& written);

}  // namespace vs11::irradiance
