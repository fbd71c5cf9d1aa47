// Where the nine-coefficient method fails, measured (the findings of `irrmap stability`):
//   1. small bright lights: one light swept from a hemisphere down to a sun-sized disk at constant
//      power; nine terms ring (negative irradiance opposite the light), and windows trade that
//      against blur (ShWindow, irradiance/sh/sh9.h);
//   2. coarse mip levels: the error each level adds to the full-resolution coefficients, and the
//      level choice by estimated error (irradiance/sh/level_choice.h);
//   3. precision: float against double accumulation, the two programs on non-unit and zero
//      normals, denormal constants and HDR radiance on the vertex machine.
// Each Measure* function is independent and deterministic, so tests call them with small sizes.
#pragma once

#include <array>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "irradiance/io/cube_map.h"
#include "irradiance/sh/ground_truth.h"
#include "irradiance/sh/sh9.h"
#include "irradiance/sh/sh_order.h"
#include "irradiance/sh/sh_projection.h"
#include "vm/core/machine.h"
#include "vm/core/result.h"

namespace vs11::irradiance {

// ---- 1. Small bright lights and windows -------------------------------------------------------------

struct WindowVariant {
  ShWindow window = ShWindow::kNone;
  double width = 0.0;  // bands, for kHanning and kLanczos

  std::string Label() const;  // "none", "hanning 4", "dering"
};

// The windows the report compares, in this order: none, hanning and lanczos of width
// kReportWindowWidth, dering, and the non-negative fit (the report relies on none first and on
// kDeringVariant and kNonNegativeVariant).
inline constexpr std::size_t kDeringVariant = 3;
inline constexpr std::size_t kNonNegativeVariant = 4;
inline constexpr double kReportWindowWidth = 4.0;
std::vector<WindowVariant> ReportWindowVariants();

struct WindowedError {
  WindowVariant variant;
  std::array<double, kSh9Bands> factors{};  // the w_l applied (dering: those of its lambda)
  ErrorStats error;                         // windowed SH9 (eq. 7, double) against the ground truth
  // Lowest irradiance over the normals and channels divided by the largest true irradiance: < 0
  // where the nine terms ring below zero.
  double lowest_over_peak = 0.0;
  double absolute_over_peak = 0.0;  // error.max_absolute divided by the largest true irradiance
};

// Every variant applied to `sh` and compared with `truth` at `normals` (same length).
std::vector<WindowedError> MeasureWindows(const Sh9Rgb& sh, std::span<const glm::dvec3> normals,
                                          std::span<const glm::dvec3> truth,
                                          std::span<const WindowVariant> variants);

// The spot of the sweep: SpotParams' direction and power, only the radius changes.
struct SpotSweepRow {
  double radius_degrees = 0.0;
  // Irradiance facing the light as the cube map holds it (ground truth at its axis), against the
  // nominal 5: texels only approximate a disk of a texel or two.
  double captured_irradiance = 0.0;
  std::vector<WindowedError> windows;  // in the order of the variants
};

// One radius of the sweep at `face_size` (>= 1), coefficients by ProjectDirect, ground truth by
// brute force at `normals` on `threads` threads.
SpotSweepRow MeasureSpot(double radius_degrees, int face_size, std::span<const glm::dvec3> normals,
                         std::span<const WindowVariant> variants, int threads);

// The largest radius of `rows` (sorted by decreasing radius) from which on every smaller one has
// windows[variant].error.max_relative > threshold; 0 when the smallest radius does not exceed it.
double RadiusWhereErrorExceeds(std::span<const SpotSweepRow> rows, std::size_t variant, double threshold);
// The same for lowest_over_peak < 0 (ringing below zero).
double RadiusWhereNegative(std::span<const SpotSweepRow> rows, std::size_t variant);

// ---- 2. Coarse mip levels --------------------------------------------------------------------------

struct LevelRow {
  int level = 0;
  int size = 0;
  double error_vs_full = 0.0;   // the level's irradiance against level 0's, in the study's metric
  double estimated = 0.0;       // EstimateLevelErrors: from this level and the next finer one only
  double max_vs_truth = 0.0;    // against brute-force integration: max and mean relative, peak, RMS
  double mean_vs_truth = 0.0;
  double peak_vs_truth = 0.0;
  double rms_vs_truth = 0.0;
};

struct LevelStudy {
  std::string environment;
  std::vector<LevelRow> rows;  // level 0 first
  int first_over_one_percent = -1;  // finest level whose error_vs_full exceeds 1 %; -1 if none
  int picked = 0;                   // CoarsestLevelWithin(estimated, max_error)
  bool pick_meets = false;          // rows[picked].error_vs_full <= max_error
  bool coarser_fails = false;       // the next coarser level exceeds max_error (true at the 1x1 end)

  // The (program, level) choice (irradiance/sh/sh_order.h) for the same max_error: every pair's
  // estimate (as irrmap makes it) and its true error against order 2 at level 0, in the same order.
  std::vector<ProgramLevelEstimate> pairs;
  std::vector<double> pair_errors;
  ProgramChoice program;
  double program_error = 0.0;  // the pick's true error against order 2 at level 0
  bool program_meets = false;  // program_error <= max_error
  ErrorStats program_vs_truth;  // the pick against the ground truth
};

// The pick of ChooseProgramAndLevel among study.pairs for `max_error` with the estimates remade
// with `factor` (kOrderErrorEstimateFactor: irrmap's own), and its true error.
struct ProgramPick {
  ProgramChoice choice;
  double error = 0.0;
};
ProgramPick PickProgram(const LevelStudy& study, double max_error, double factor = kOrderErrorEstimateFactor);

// Every level of `env` (face size a power of two equal to basis.face_size; asserted) with
// `max_error` for the pick, which bounds `metric`'s figure (as irrmap --error-metric: every error
// against level 0 and every estimate is in it). `normals` are those of the errors against level 0 and the truth; the
// estimate uses irrmap's own (SphereNormals(kLevelErrorNormals)), as irrmap does.
LevelStudy MeasureLevels(std::string environment, const CubeMap& env, const BasisPyramid& basis,
                         std::span<const glm::dvec3> normals, double max_error, int threads,
                         ErrorMetric metric = kDefaultErrorMetric);

// Why coarse levels fail: the same small spot centred on a face, on the edge between two faces and
// at a cube corner, and the error of each level against level 0. A coarse texel spreads its mean
// radiance over its block as if the light filled it, weighted by the block's summed basis x solid
// angle; where that weight varies across the block (at edges and corners the texel solid angles
// shrink fivefold and the basis turns fastest in texel units) the misplaced light costs most.
struct SpotPlacementRow {
  int level = 0;
  int size = 0;
  double face_centre = 0.0;  // error_vs_full with the spot at +y's centre
  double face_edge = 0.0;    // at the middle of the +x/+z edge
  double cube_corner = 0.0;  // at the (1, 1, 1) corner
};
std::vector<SpotPlacementRow> MeasureSpotPlacement(double radius_degrees, const BasisPyramid& basis,
                                                   std::span<const glm::dvec3> normals);

// ---- 3. Precision ---------------------------------------------------------------------------------

// ProjectDirect with every product added to one float running sum per coefficient and channel,
// the naive way (ProjectDirect sums rows in double): what float accumulation would cost.
Sh9Rgb ProjectDirectFloatSums(const CubeMap& env);

struct AccumulationPrecision {
  int face_size = 0;
  double coefficient_error = 0.0;  // max over the 27 of |float - double| / |L00| (largest channel)
  double irradiance_error = 0.0;   // IrradianceDifference(float sums, double sums)
};
AccumulationPrecision MeasureFloatAccumulation(const CubeMap& env, std::span<const glm::dvec3> normals);

// The paper's 11-slot program and the 10-slot unit-sphere program on the vertex machine, fed
// `length` x unit normals. Errors are max over normals and channels of |program - E(unit normal)|
// divided by the largest E.
struct NormalLengthRow {
  double length = 1.0;
  double paper_error = 0.0;
  double unit10_error = 0.0;
  double programs_difference = 0.0;  // max |paper - unit10| / largest E
};
// What the two programs give for the zero vector (per channel), in units of the mean irradiance
// c0 L00: paper c0 L00 - c3 L20, unit10 c0 L00 + 2 c3 L20.
struct ZeroNormalResult {
  glm::dvec3 paper{0.0};
  glm::dvec3 unit10{0.0};
  bool finite = false;
};
struct ProgramPrecision {
  std::vector<NormalLengthRow> lengths;
  ZeroNormalResult zero_normal;
};
// `lengths` > 0. An error (kEmbeddedProgram) when a program fails to load.
Result<ProgramPrecision> MeasureNormalLengths(const Sh9Rgb& sh, std::span<const glm::dvec3> unit_normals,
                                              std::span<const double> lengths);

// The coefficients scaled by `scale` and run through the paper's program on both engines, against
// the scaled double polynomial (eq. 7). Tiny scales make the seven constants denormal floats.
struct ScaledRun {
  double scale = 1.0;
  bool constants_denormal = false;  // some packed register component is a nonzero denormal
  double reference_error = 0.0;     // max relative (floor 1 %) of the reference engine
  double batch_error = 0.0;         // the same, batch engine
  bool engines_identical = false;   // bit for bit
};
Result<std::vector<ScaledRun>> MeasureScaledRuns(const Sh9Rgb& sh, std::span<const glm::dvec3> normals,
                                                 std::span<const double> scales);

// The sky with its sun given radiance `sun_radiance` (1e6: an HDR capture of the real sun): the
// program on the machine against double eq. 7, and SH9 against the ground truth.
struct HdrResult {
  double sun_radiance = 0.0;
  double peak_irradiance = 0.0;
  double program_error = 0.0;  // max |program - eq. 7| / peak
  double relative_to_truth_max = 0.0;  // SH9 against the ground truth, max relative
};
// The default sky with a sun of angular radius kHdrSunRadiusDegrees and radiance `sun_radiance`.
inline constexpr double kHdrSunRadiusDegrees = 0.5;
CubeMap MakeHdrSky(int face_size, double sun_radiance);
Result<HdrResult> MeasureHdrSky(int face_size, double sun_radiance, std::span<const glm::dvec3> normals, int threads);

// A black environment and the zero vector: every stage stays finite and exactly zero.
struct ZeroEnvironmentResult {
  bool coefficients_zero = false;
  bool program_zero = false;      // the paper's program gives 0 at every normal
  bool error_stats_finite = false;  // CompareIrradiance(zero, zero)
  double dering_lambda = -1.0;
  int picked_level = -1;
};
Result<ZeroEnvironmentResult> MeasureZeroEnvironment(int face_size, std::span<const glm::dvec3> normals);

}  // namespace vs11::irradiance
