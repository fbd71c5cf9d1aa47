// Stability measurements. See stability.h.
#include "irradiance/report/stability.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <optional>
#include <utility>

#include <fmt/format.h>

#include "irradiance/io/environments.h"
#include "irradiance/report/paper_program.h"
#include "irradiance/sh/level_choice.h"
#include "irradiance/sh/nonneg_fit.h"
#include "programs/embedded_programs.h"

namespace vs11::irradiance {
namespace {

// Relative errors against a truth that is zero behind a single light use CompareIrradiance's floor.
constexpr double kFloorFraction = 0.01;
constexpr double kOnePercent = 0.01;
// The 1 x 1 x 1 corner of the cube is 35.26 degrees above the horizon (asin(1 / sqrt 3)).
constexpr double kCornerElevationDegrees = 35.264389682754654;

double LargestComponent(std::span<const glm::dvec3> values) {
  double largest = 0.0;
  for (const glm::dvec3& v : values) largest = std::max({largest, std::abs(v.x), std::abs(v.y), std::abs(v.z)});
  return largest;
}

double LowestComponent(std::span<const glm::dvec3> values) {
  double lowest = std::numeric_limits<double>::infinity();
  for (const glm::dvec3& v : values) lowest = std::min({lowest, v.x, v.y, v.z});
  return values.empty() ? 0.0 : lowest;
}

std::vector<glm::dvec3> Eq7At(const Sh9Rgb& sh, std::span<const glm::dvec3> normals) {
  std::vector<glm::dvec3> values;
  values.reserve(normals.size());
  for (const glm::dvec3& n : normals) values.push_back(IrradianceEq7(sh, n));
  return values;
}

// Max over samples and channels of |a - b| divided by `scale`.
double MaxDifference(std::span<const glm::dvec3> a, std::span<const glm::dvec3> b, double scale) {
  assert(a.size() == b.size());
  double largest = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const glm::dvec3 d = glm::abs(a[i] - b[i]);
    largest = std::max({largest, d.x, d.y, d.z});
  }
  return scale > 0.0 ? largest / scale : largest;
}

Sh9Rgb Scaled(const Sh9Rgb& sh, double scale) {
  Sh9Rgb scaled = sh;
  for (glm::dvec3& c : scaled.coefficients) c *= scale;
  return scaled;
}

Result<PaperProgram> LoadUnit10() {
  return PaperProgram::LoadEmbedded("sh9_irradiance_unit10.vsh", programs::kProgramSh9IrradianceUnit10);
}

std::vector<Sh9Rgb> AllLevels(const CubeMap& env, const BasisPyramid& basis) {
  assert(env.face_size == basis.face_size);
  std::optional<CubeMipChain> mips = BuildEnvironmentMips(env);
  assert(mips);
  std::vector<Sh9Rgb> levels;
  for (std::size_t level = 0; level < mips->levels.size(); ++level) {
    levels.push_back(ProjectLevel(*mips, basis, static_cast<int>(level)));
  }
  return levels;
}

}  // namespace

// ---- 1. Small bright lights and windows -------------------------------------------------------------

std::string WindowVariant::Label() const {
  if (window == ShWindow::kHanning || window == ShWindow::kLanczos) {
    return fmt::format("{} {:g}", ShWindowName(window), width);
  }
  return std::string(ShWindowName(window));
}

std::vector<WindowVariant> ReportWindowVariants() {
  return {{ShWindow::kNone, 0.0},
          {ShWindow::kHanning, kReportWindowWidth},
          {ShWindow::kLanczos, kReportWindowWidth},
          {ShWindow::kDering, 0.0},
          {ShWindow::kNonNegative, 0.0}};
}

std::vector<WindowedError> MeasureWindows(const Sh9Rgb& sh, std::span<const glm::dvec3> normals,
                                          std::span<const glm::dvec3> truth,
                                          std::span<const WindowVariant> variants) {
  assert(normals.size() == truth.size());
  const double peak = LargestComponent(truth);
  std::vector<WindowedError> rows;
  for (const WindowVariant& variant : variants) {
    WindowedError row;
    row.variant = variant;
    Sh9Rgb windowed;
    if (variant.window == ShWindow::kNonNegative) {
      row.factors = {1.0, 1.0, 1.0};
      windowed = FitNonNegative(sh);
    } else {
      row.factors = variant.window == ShWindow::kDering ? LaplacianWindowFactors(DeringLambda(sh, normals))
                                                        : ShWindowFactors(variant.window, variant.width);
      windowed = ApplyShWindow(sh, row.factors);
    }
    const std::vector<glm::dvec3> estimate = Eq7At(windowed, normals);
    row.error = CompareIrradiance(estimate, truth, normals, kFloorFraction);
    row.lowest_over_peak = peak > 0.0 ? LowestComponent(estimate) / peak : 0.0;
    row.absolute_over_peak = peak > 0.0 ? row.error.max_absolute / peak : 0.0;
    rows.push_back(row);
  }
  return rows;
}

SpotSweepRow MeasureSpot(double radius_degrees, int face_size, std::span<const glm::dvec3> normals,
                         std::span<const WindowVariant> variants, int threads) {
  SpotParams params;
  params.angular_radius_degrees = radius_degrees;
  const CubeMap env = MakeSpot(face_size, params);
  std::vector<glm::dvec3> truth_normals(normals.begin(), normals.end());
  truth_normals.push_back(DirectionFromAzimuthElevation(params.azimuth_degrees, params.elevation_degrees));
  std::vector<glm::dvec3> truth = GroundTruthIrradiance(env, truth_normals, threads);
  SpotSweepRow row;
  row.radius_degrees = radius_degrees;
  row.captured_irradiance = truth.back().x;
  truth.pop_back();
  row.windows = MeasureWindows(ProjectDirect(env), normals, truth, variants);
  return row;
}

double RadiusWhereErrorExceeds(std::span<const SpotSweepRow> rows, std::size_t variant, double threshold) {
  double radius = 0.0;
  for (auto row = rows.rbegin(); row != rows.rend() && row->windows[variant].error.max_relative > threshold; ++row) {
    radius = row->radius_degrees;
  }
  return radius;
}

double RadiusWhereNegative(std::span<const SpotSweepRow> rows, std::size_t variant) {
  double radius = 0.0;
  for (auto row = rows.rbegin(); row != rows.rend() && row->windows[variant].lowest_over_peak < 0.0; ++row) {
    radius = row->radius_degrees;
  }
  return radius;
}

// ---- 2. Coarse mip levels --------------------------------------------------------------------------

LevelStudy MeasureLevels(std::string environment, const CubeMap& env, const BasisPyramid& basis,
                         std::span<const glm::dvec3> normals, double max_error, int threads, ErrorMetric metric) {
  const std::vector<Sh9Rgb> levels = AllLevels(env, basis);
  // The estimate sees only what irrmap sees: its own normals, no level 0 and no truth.
  const std::vector<double> estimated = EstimateLevelErrors(levels, SphereNormals(kLevelErrorNormals), metric);
  const std::vector<glm::dvec3> truth = GroundTruthIrradiance(env, normals, threads);
  LevelStudy study;
  study.environment = std::move(environment);
  for (std::size_t k = 0; k < levels.size(); ++k) {
    LevelRow row;
    row.level = static_cast<int>(k);
    row.size = env.face_size >> k;
    row.error_vs_full = IrradianceDifference(levels[k], levels[0], normals, metric);
    row.estimated = estimated[k];
    const ErrorStats error = CompareIrradiance(Eq7At(levels[k], normals), truth, kFloorFraction);
    row.max_vs_truth = error.max_relative;
    row.mean_vs_truth = error.mean_relative;
    row.peak_vs_truth = error.max_peak;
    row.rms_vs_truth = error.max_rms;
    if (study.first_over_one_percent < 0 && row.error_vs_full > kOnePercent) study.first_over_one_percent = row.level;
    study.rows.push_back(row);
  }
  study.picked = CoarsestLevelWithin(estimated, max_error);
  study.pick_meets = study.rows[study.picked].error_vs_full <= max_error;
  const std::size_t coarser = static_cast<std::size_t>(study.picked) + 1;
  study.coarser_fails = coarser == study.rows.size() || study.rows[coarser].error_vs_full > max_error;

  study.pairs = EstimateProgramLevelErrors(levels, estimated, SphereNormals(kLevelErrorNormals), metric);
  for (const ProgramLevelEstimate& pair : study.pairs) {
    study.pair_errors.push_back(
        IrradianceDifference(ReduceToOrder(levels[pair.level], pair.order), levels[0], normals, metric));
  }
  const ProgramPick pick = PickProgram(study, max_error);
  study.program = pick.choice;
  study.program_error = pick.error;
  study.program_meets = pick.error <= max_error;
  study.program_vs_truth = CompareIrradiance(
      Eq7At(ReduceToOrder(levels[pick.choice.level], pick.choice.order), normals), truth, kFloorFraction);
  return study;
}

ProgramPick PickProgram(const LevelStudy& study, double max_error, double factor) {
  std::vector<double> level_estimates;
  for (const LevelRow& row : study.rows) level_estimates.push_back(row.estimated);
  std::vector<ProgramLevelEstimate> pairs = study.pairs;
  for (ProgramLevelEstimate& pair : pairs) {
    pair.estimated = level_estimates[static_cast<std::size_t>(pair.level)] + factor * pair.order_difference;
  }
  ProgramPick pick;
  pick.choice = ChooseProgramAndLevel(pairs, level_estimates, max_error);
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    if (pairs[i].order == pick.choice.order && pairs[i].level == pick.choice.level) pick.error = study.pair_errors[i];
  }
  return pick;
}

std::vector<SpotPlacementRow> MeasureSpotPlacement(double radius_degrees, const BasisPyramid& basis,
                                                   std::span<const glm::dvec3> normals) {
  struct Placement {
    double azimuth, elevation;
  };
  const std::array<Placement, 3> placements = {{{0.0, 90.0}, {45.0, 0.0}, {45.0, kCornerElevationDegrees}}};
  std::array<std::vector<Sh9Rgb>, 3> levels;
  for (std::size_t p = 0; p < placements.size(); ++p) {
    SpotParams params;
    params.azimuth_degrees = placements[p].azimuth;
    params.elevation_degrees = placements[p].elevation;
    params.angular_radius_degrees = radius_degrees;
    levels[p] = AllLevels(MakeSpot(basis.face_size, params), basis);
  }
  std::vector<SpotPlacementRow> rows;
  for (std::size_t k = 0; k < levels[0].size(); ++k) {
    SpotPlacementRow row;
    row.level = static_cast<int>(k);
    row.size = basis.face_size >> k;
    row.face_centre = IrradianceDifference(levels[0][k], levels[0][0], normals, ErrorMetric::kRelative);
    row.face_edge = IrradianceDifference(levels[1][k], levels[1][0], normals, ErrorMetric::kRelative);
    row.cube_corner = IrradianceDifference(levels[2][k], levels[2][0], normals, ErrorMetric::kRelative);
    rows.push_back(row);
  }
  return rows;
}

// ---- 3. Precision ---------------------------------------------------------------------------------

Sh9Rgb ProjectDirectFloatSums(const CubeMap& env) {
  const int size = env.face_size;
  std::array<glm::vec3, kSh9Coefficients> sums{};
  std::vector<float> solid_angles(static_cast<std::size_t>(size));
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) solid_angles[x] = static_cast<float>(TexelSolidAngle(x, y, size));
    for (CubeFace face : kAllCubeFaces) {
      const Image& image = env.face(face);
      for (int x = 0; x < size; ++x) {
        const std::array<double, kSh9Coefficients> basis = ShBasis(TexelDirection(face, x, y, size));
        const glm::vec3 weighted = image.at(x, y) * solid_angles[x];
        for (int i = 0; i < kSh9Coefficients; ++i) sums[i] += static_cast<float>(basis[i]) * weighted;
      }
    }
  }
  Sh9Rgb sh;
  for (int i = 0; i < kSh9Coefficients; ++i) sh.coefficients[i] = glm::dvec3(sums[i]);
  return sh;
}

AccumulationPrecision MeasureFloatAccumulation(const CubeMap& env, std::span<const glm::dvec3> normals) {
  const Sh9Rgb exact = ProjectDirect(env);
  const Sh9Rgb floats = ProjectDirectFloatSums(env);
  const double l00 = LargestComponent(std::span(&exact.coefficients[0], 1));
  AccumulationPrecision result;
  result.face_size = env.face_size;
  result.coefficient_error = MaxDifference(floats.coefficients, exact.coefficients, l00);
  result.irradiance_error = IrradianceDifference(floats, exact, normals, ErrorMetric::kRelative);
  return result;
}

Result<ProgramPrecision> MeasureNormalLengths(const Sh9Rgb& sh, std::span<const glm::dvec3> unit_normals,
                                              std::span<const double> lengths) {
  ProgramPrecision result;
  const Result<PaperProgram> paper = PaperProgram::Load();
  if (!paper) return paper.error();
  const Result<PaperProgram> unit10 = LoadUnit10();
  if (!unit10) return unit10.error();
  const SevenConstants table1 = PackTable1(sh);
  const SevenConstants sphere10 = PackUnitSphere10(sh);
  const std::vector<glm::dvec3> truth = Eq7At(sh, unit_normals);
  const double peak = LargestComponent(truth);
  for (double length : lengths) {
    std::vector<glm::dvec3> normals;
    for (const glm::dvec3& n : unit_normals) normals.push_back(length * n);
    // The batch engine never fails (the CPU engines' Run returns no error).
    const std::vector<glm::dvec3> a = paper->Irradiance(table1, normals, "batch").value();
    const std::vector<glm::dvec3> b = unit10->Irradiance(sphere10, normals, "batch").value();
    result.lengths.push_back({length, MaxDifference(a, truth, peak), MaxDifference(b, truth, peak),
                              MaxDifference(a, b, peak)});
  }
  const std::array<glm::dvec3, 1> zero = {glm::dvec3(0.0)};
  const glm::dvec3 mean = kShC0 * sh.coefficients[ShIndex(0, 0)];
  const std::array<glm::dvec3, 2> zero_outputs = {paper->Irradiance(table1, zero, "batch").value()[0],
                                                  unit10->Irradiance(sphere10, zero, "batch").value()[0]};
  result.zero_normal.paper = zero_outputs[0] / mean;
  result.zero_normal.unit10 = zero_outputs[1] / mean;
  result.zero_normal.finite = std::isfinite(LargestComponent(zero_outputs));
  return result;
}

Result<std::vector<ScaledRun>> MeasureScaledRuns(const Sh9Rgb& sh, std::span<const glm::dvec3> normals,
                                                 std::span<const double> scales) {
  std::vector<ScaledRun> runs;
  const Result<PaperProgram> paper = PaperProgram::Load();
  if (!paper) return paper.error();
  for (double scale : scales) {
    const Sh9Rgb scaled = Scaled(sh, scale);
    const SevenConstants constants = PackTable1(scaled);
    ScaledRun run;
    run.scale = scale;
    for (const glm::vec4& r : constants.registers) {
      for (int c = 0; c < 4; ++c) run.constants_denormal |= std::fpclassify(r[c]) == FP_SUBNORMAL;
    }
    const std::vector<glm::dvec3> truth = Eq7At(scaled, normals);
    const std::vector<glm::dvec3> reference = paper->Irradiance(constants, normals, "ref").value();
    const std::vector<glm::dvec3> batch = paper->Irradiance(constants, normals, "batch").value();
    run.reference_error = CompareIrradiance(reference, truth, kFloorFraction).max_relative;
    run.batch_error = CompareIrradiance(batch, truth, kFloorFraction).max_relative;
    run.engines_identical = reference == batch;
    runs.push_back(run);
  }
  return runs;
}

CubeMap MakeHdrSky(int face_size, double sun_radiance) {
  SkyParams params;
  params.sun_angular_radius_degrees = kHdrSunRadiusDegrees;
  const double sin_r = std::sin(kHdrSunRadiusDegrees * std::numbers::pi / 180.0);
  params.sun_irradiance = glm::vec3(static_cast<float>(sun_radiance * std::numbers::pi * sin_r * sin_r));
  return MakeSky(face_size, params);
}

Result<HdrResult> MeasureHdrSky(int face_size, double sun_radiance, std::span<const glm::dvec3> normals, int threads) {
  HdrResult result;
  result.sun_radiance = sun_radiance;
  const Result<PaperProgram> paper = PaperProgram::Load();
  if (!paper) return paper.error();
  const CubeMap env = MakeHdrSky(face_size, sun_radiance);
  const Sh9Rgb sh = ProjectDirect(env);
  const std::vector<glm::dvec3> truth = GroundTruthIrradiance(env, normals, threads);
  const std::vector<glm::dvec3> eq7 = Eq7At(sh, normals);
  result.peak_irradiance = LargestComponent(truth);
  result.program_error =
      MaxDifference(paper->Irradiance(PackTable1(sh), normals, "batch").value(), eq7, result.peak_irradiance);
  result.relative_to_truth_max = CompareIrradiance(eq7, truth, kFloorFraction).max_relative;
  return result;
}

Result<ZeroEnvironmentResult> MeasureZeroEnvironment(int face_size, std::span<const glm::dvec3> normals) {
  ZeroEnvironmentResult result;
  const Result<PaperProgram> paper = PaperProgram::Load();
  if (!paper) return paper.error();
  const CubeMap black = MakeConstant(face_size, glm::vec3(0.0f));
  const Sh9Rgb sh = ProjectDirect(black);
  result.coefficients_zero = std::all_of(sh.coefficients.begin(), sh.coefficients.end(),
                                         [](const glm::dvec3& c) { return c == glm::dvec3(0.0); });
  std::vector<glm::dvec3> with_zero(normals.begin(), normals.end());
  with_zero.push_back(glm::dvec3(0.0));
  const std::vector<glm::dvec3> output = paper->Irradiance(PackTable1(sh), with_zero, "batch").value();
  result.program_zero = LargestComponent(output) == 0.0 && LowestComponent(output) == 0.0;
  const ErrorStats stats = CompareIrradiance(output, output, kFloorFraction);
  result.error_stats_finite = std::isfinite(stats.max_relative) && std::isfinite(stats.mean_relative);
  result.dering_lambda = DeringLambda(sh, normals);
  std::optional<BasisPyramid> basis = BuildBasisPyramid(face_size);
  if (basis) {
    const std::vector<Sh9Rgb> levels = AllLevels(black, *basis);
    result.picked_level =
        CoarsestLevelWithin(EstimateLevelErrors(levels, normals, kDefaultErrorMetric), kDefaultMaxLevelError);
  }
  return result;
}

}  // namespace vs11::irradiance
