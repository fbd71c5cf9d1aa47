// The speed/accuracy sweep behind `irrmap chart`: for each environment, every mip level x each
// projection method, the time of one coefficient update against the error of the irradiance the
// paper's program computes from those coefficients (the same errors as irrmap's level table:
// CompareIrradiance against GroundTruthIrradiance at SphereNormals).
//
// Methods (both from the mip pyramid's level k, whose faces are face_size >> k):
//   kMipPyramid     ProjectLevel(k): the paper's acceleration, level k's mean radiance times the
//                   basis pyramid (each weight the sum of the basis over the finest texels it covers)
//   kDirectOnLevel  ProjectDirect(level k's map): the basis evaluated at the coarse texel centres, as
//                   if level k were the environment itself; at level 0 this is the plain
//                   full-resolution projection (the reference irrmap checks ProjectLevel(0) against)
// The order dimension (irradiance/sh/sh_order.h): for kMipPyramid, every level also gives points for
// the reduced programs (order0, order1, zh3), their irradiance computed by their own vs_1_1 program
// from the same coefficients; their update time is the same projection's (the reduction is a few
// multiplications), and what they save is slots per vertex.
// The update time excludes building the mips (done once per environment change, the same for every
// level and method; reported per environment as mips_ms) and the basis pyramid (once per face size).
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "irradiance/io/environment_io.h"
#include "irradiance/render/gnuplot.h"
#include "irradiance/sh/ground_truth.h"
#include "irradiance/report/paper_program.h"
#include "vm/core/name_table.h"
#include "vm/core/result.h"

namespace vs11::irradiance {

enum class ProjectionMethod { kMipPyramid, kDirectOnLevel };
inline constexpr ProjectionMethod kAllProjectionMethods[] = {ProjectionMethod::kMipPyramid,
                                                             ProjectionMethod::kDirectOnLevel};
// The CSV's method column.
inline constexpr NameTable kProjectionMethodNames("projection method", {
    Choice(ProjectionMethod::kMipPyramid, "mip", "the mip pyramid's level"),
    Choice(ProjectionMethod::kDirectOnLevel, "direct", "projected at the level's size directly")});

struct SpeedAccuracyOptions {
  // Files, {face} patterns or built-in names, as irrmap's ENV; empty: every built-in.
  std::vector<std::string> environments;
  EnvironmentLayout layout = EnvironmentLayout::kAuto;  // files only
  int face_size = kDefaultFaceSize;         // built-ins, and cubes resampled from lat-long/angular maps
  int error_normals = kDefaultErrorNormals;
  int threads = 0;              // ground truth and the vertex program; 0: every core
  // Timing: an update is repeated until min_batch_ms have passed (a batch), `batches` times; the
  // median of the batch means is reported, which shrugs off a batch slowed by another process.
  double min_batch_ms = 20.0;
  int batches = 3;
  // The error on the chart's axis (ChartErrorFigure).
  ErrorMetric error_metric = kDefaultErrorMetric;
};

struct SpeedAccuracyPoint {
  std::string environment;  // as given (a built-in name or a path)
  ProjectionMethod method = ProjectionMethod::kMipPyramid;
  int level = 0;
  int size = 0;              // face size at the level
  ShOrder order = ShOrder::kOrder2;  // the program evaluating the coefficients
  double update_ms = 0.0;    // median batch mean of one projection
  ErrorStats error;
};

struct SpeedAccuracyEnvironment {
  std::string name;
  int face_size = 0;
  double mips_ms = 0.0;  // one RefillEnvironmentMips of this environment (median batch mean)
};

struct SpeedAccuracyResult {
  ErrorMetric metric = kDefaultErrorMetric;  // on the chart's axis
  std::vector<SpeedAccuracyEnvironment> environments;
  // Environment, then method, then level from 0, each mip level's order-2 point followed by its
  // reduced orders' points.
  std::vector<SpeedAccuracyPoint> points;
  std::vector<std::string> warnings;
};

// Progress: the environment being measured (index from 0 of `count`).
using SpeedAccuracyProgress = std::function<void(std::string_view environment, int index, int count)>;

// What is wrong with the options themselves (a bad value: a usage error; kOptionValue or kFaceSize),
// or success.
Status CheckSpeedAccuracyOptions(const SpeedAccuracyOptions& options);

// Runs the sweep. Success, or the error that says what is wrong (a bad option, an environment that
// cannot be loaded or whose face size is not a power of two).
Status RunSpeedAccuracySweep(const SpeedAccuracyOptions& options, SpeedAccuracyResult& result,
                             const SpeedAccuracyProgress& progress = {});

// One header line, then one line per point:
//   environment,method,level,size,update_ms,mips_ms,mean_relative_error,max_relative_error,order,slots,
//   peak_error,rms_error
// (peak_error and rms_error as ErrorStats::max_peak and max_rms, the same figures as irrmap's level
// table and coeffs.json for the same level).
std::string SpeedAccuracyCsv(const SpeedAccuracyResult& result);

// The figure the chart plots for `metric`: mean_relative (kRelative, the chart's figure before the
// metrics existed), max_peak (kPeak) or max_rms (kRms).
double ChartErrorFigure(const ErrorStats& error, ErrorMetric metric);
// The environment as the chart's key names it: the file's base name ("probulator_grace.hdr"), a
// built-in's name as it is.
std::string ChartEnvironmentName(const std::string& environment);

// Two panels. Left: time per update (log x) against ChartErrorFigure in percent (log y) of the
// paper's program (order 2): one colour per environment, solid lines for kMipPyramid and dashed for
// kDirectOnLevel, each point labelled by its level. Right: slots per vertex of each order's program
// (1, 3, 6, 11) against the same error from the full-resolution coefficients (solid) and from the
// 16x16 level (dashed, where the face size has one), one colour per environment. Curves are titled
// by ChartEnvironmentName, printed as written (GnuplotLiteral).
GnuplotChart SpeedAccuracyChart(const SpeedAccuracyResult& result);

// The file names written into an output folder.
inline constexpr std::string_view kSpeedAccuracyCsv = "speed_accuracy.csv";
inline constexpr std::string_view kSpeedAccuracySvg = "speed_accuracy.svg";
inline constexpr std::string_view kSpeedAccuracyPng = "speed_accuracy.png";

// Writes the three files into `out_dir` (created if needed). Each is written to a temporary and
// renamed; if any fails, the ones already in place from this call are removed again. Success, with
// the paths written in `written`, or the error.
Status WriteSpeedAccuracy(const SpeedAccuracyResult& result, const std::filesystem::path& out_dir,
                          std::vector<std::filesystem::path>& written);

}  // namespace vs11::irradiance
