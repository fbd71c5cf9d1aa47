// Regression tests of the findings of `irrmap stability` (irradiance/report/stability.h), each with its
// threshold, at face sizes small enough for the whole file to take about a second.
#include "irradiance/report/stability.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "irradiance/io/environments.h"
#include "irradiance/jobs/irrmap_job.h"
#include "irradiance/report/stability_report.h"
#include "irradiance/sh/level_choice.h"

namespace vs11::irradiance {
namespace {

namespace fs = std::filesystem;
using testing::HasSubstr;

constexpr int kFaceSize = 32;
constexpr int kNormals = 400;
// A point light's nine-term kernel 1/4 + t/2 + 5/32 (3t^2 - 1) dips to -0.0396 (t = -8/15), in
// units of the true peak; rounding and the normal sampling move the minimum found by < 1e-4.
constexpr double kPointLightDip = -0.0396;
constexpr double kDipTolerance = 2e-4;

std::size_t VariantIndex(ShWindow window) {
  const std::vector<WindowVariant> variants = ReportWindowVariants();
  return static_cast<std::size_t>(std::find_if(variants.begin(), variants.end(),
                                               [&](const WindowVariant& v) { return v.window == window; }) -
                                  variants.begin());
}

// ---- Windows ----------------------------------------------------------------------------------------

TEST(ShWindowTest, FactorsFollowTheirFormulas) {
  const auto none = ShWindowFactors(ShWindow::kNone, 0.0);
  EXPECT_EQ(none[1], 1.0);
  EXPECT_EQ(none[2], 1.0);
  const auto hanning = ShWindowFactors(ShWindow::kHanning, 4.0);
  EXPECT_NEAR(hanning[1], 0.5 * (1.0 + std::cos(std::numbers::pi / 4.0)), 1e-15);
  EXPECT_NEAR(hanning[2], 0.5, 1e-15);
  const auto lanczos = ShWindowFactors(ShWindow::kLanczos, 4.0);
  EXPECT_NEAR(lanczos[2], 2.0 / std::numbers::pi, 1e-15);  // sinc(1/2)
  EXPECT_EQ(ShWindowFactors(ShWindow::kHanning, 2.0)[2], 0.0);  // band 2 at the window's edge
  EXPECT_EQ(ShWindowFactors(ShWindow::kLanczos, 1.5)[2], 0.0);
  const auto laplacian = LaplacianWindowFactors(0.5);
  EXPECT_DOUBLE_EQ(laplacian[1], 1.0 / 3.0);
  EXPECT_DOUBLE_EQ(laplacian[2], 1.0 / 19.0);
  for (ShWindow w : {ShWindow::kNone, ShWindow::kHanning, ShWindow::kLanczos, ShWindow::kDering}) {
    EXPECT_EQ(kShWindowNames.Find(ShWindowName(w)), w);
  }
  EXPECT_EQ(kShWindowNames.Find("hamming"), std::nullopt);
}

TEST(ShWindowTest, ApplyScalesEachBand) {
  Sh9Rgb sh;
  for (int i = 0; i < kSh9Coefficients; ++i) sh.coefficients[i] = glm::dvec3(i + 1.0);
  const Sh9Rgb windowed = ApplyShWindow(sh, {1.0, 0.5, 0.25});
  EXPECT_EQ(windowed.at(0, 0), glm::dvec3(1.0));
  EXPECT_EQ(windowed.at(1, 1), glm::dvec3(2.0));    // index 3 -> 4 x 0.5
  EXPECT_EQ(windowed.at(2, 2), glm::dvec3(2.25));   // index 8 -> 9 x 0.25
}

// Finding 1a: the dip of a point light, straight from the basis (no cube map involved).
TEST(ShWindowTest, PointLightRingsToMinus4PercentAndDeringingMakesItNonNegative) {
  const glm::dvec3 light = glm::normalize(glm::dvec3(0.3, 0.8, -0.5));
  Sh9Rgb sh;  // radiance = delta(light) of unit power: L_lm = y_lm(light)
  const auto basis = ShBasis(light);
  for (int i = 0; i < kSh9Coefficients; ++i) sh.coefficients[i] = glm::dvec3(basis[i]);
  const std::vector<glm::dvec3> normals = SphereNormals(20000);
  auto lowest = [&](const Sh9Rgb& coefficients) {
    double low = 0.0;
    for (const glm::dvec3& n : normals) low = std::min(low, IrradianceEq7(coefficients, n).x);
    return low;
  };
  EXPECT_NEAR(lowest(sh), kPointLightDip, kDipTolerance);
  // The usual windows only soften the dip (measured: hanning 4 -2.24 %, lanczos 4 -1.92 %).
  EXPECT_LT(lowest(ApplyShWindow(sh, ShWindowFactors(ShWindow::kHanning, 4.0))), -0.015);
  EXPECT_LT(lowest(ApplyShWindow(sh, ShWindowFactors(ShWindow::kLanczos, 4.0))), -0.015);
  const double lambda = DeringLambda(sh, normals);
  EXPECT_GT(lambda, 0.0);
  EXPECT_GE(lowest(ApplyShWindow(sh, LaplacianWindowFactors(lambda))), -1e-9);
  // The smallest such lambda: 1 % less leaves a dip.
  EXPECT_LT(lowest(ApplyShWindow(sh, LaplacianWindowFactors(0.99 * lambda))), 0.0);
}

// ---- Finding 1: the light sweep ------------------------------------------------------------------

class SpotSweep : public testing::Test {
 protected:
  static void SetUpTestSuite() {
    const std::vector<glm::dvec3> normals = SphereNormals(kNormals);
    const std::vector<WindowVariant> variants = ReportWindowVariants();
    for (double radius : {90.0, 2.0}) rows_.push_back(MeasureSpot(radius, kFaceSize, normals, variants, 2));
  }
  static std::vector<SpotSweepRow> rows_;
};
std::vector<SpotSweepRow> SpotSweep::rows_;

TEST_F(SpotSweep, AHemisphereLightDoesNotRing) {
  const WindowedError& none = rows_[0].windows[VariantIndex(ShWindow::kNone)];
  EXPECT_LT(none.error.max_relative, 0.01);  // measured 0.1 %
  EXPECT_GE(none.lowest_over_peak, 0.0);
}

TEST_F(SpotSweep, ATwoDegreeLightRingsBelowZeroAndPastTenPercent) {
  const WindowedError& none = rows_[1].windows[VariantIndex(ShWindow::kNone)];
  EXPECT_LT(none.lowest_over_peak, -0.035);       // measured -3.96 %: the point-light dip
  EXPECT_GT(none.error.max_relative, 0.10);       // measured 870 % (where the truth is black)
  EXPECT_EQ(RadiusWhereNegative(rows_, VariantIndex(ShWindow::kNone)), 2.0);
  EXPECT_EQ(RadiusWhereErrorExceeds(rows_, VariantIndex(ShWindow::kNone), 0.10), 2.0);
}

TEST_F(SpotSweep, DeringRemovesTheDipAtTheCostOfMoreError) {
  const WindowedError& none = rows_[1].windows[VariantIndex(ShWindow::kNone)];
  const WindowedError& dering = rows_[1].windows[VariantIndex(ShWindow::kDering)];
  const WindowedError& hanning = rows_[1].windows[VariantIndex(ShWindow::kHanning)];
  EXPECT_GE(dering.lowest_over_peak, -1e-6);
  EXPECT_LT(hanning.lowest_over_peak, -0.015);  // measured -2.24 %: hanning 4 does not remove it
  EXPECT_GT(hanning.lowest_over_peak, none.lowest_over_peak);
  // The trade-off: dering's blur costs mean relative error (measured 5.65 against 1.67 without)
  // and absolute error (measured 42 % of the peak, against 8.8 %).
  EXPECT_GT(dering.error.mean_relative, 2.0 * none.error.mean_relative);
  EXPECT_LT(dering.error.mean_relative, 7.0);
  EXPECT_GT(dering.absolute_over_peak, 2.0 * none.absolute_over_peak);
  EXPECT_LT(dering.absolute_over_peak, 0.5);
  // Its factors: w1 about 0.59, w2 about 0.14.
  EXPECT_NEAR(dering.factors[1], 0.59, 0.03);
  EXPECT_NEAR(dering.factors[2], 0.14, 0.03);
}

TEST(StabilityTest, DeringLeavesTheSkyAlone) {
  const Sh9Rgb sky = ProjectDirect(MakeSky(kFaceSize));
  EXPECT_EQ(DeringLambda(sky, SphereNormals(kNormals)), 0.0);
}

// ---- Finding 2: coarse levels and the level pick -------------------------------------------------

TEST(StabilityTest, ErrorPassesOnePercentWhereBlocksCoverTheLights) {
  const std::optional<BasisPyramid> basis = BuildBasisPyramid(64);
  ASSERT_TRUE(basis);
  const std::vector<glm::dvec3> normals = SphereNormals(kNormals);
  // The report's finding in relative errors (floor 1 % of the peak).
  // Measured at 64: sky 0.15, 0.35, 5.4 % at 32, 16, 8; spot (3 deg) 4.7 % at 32; constant < 1e-7.
  constexpr ErrorMetric kRelative = ErrorMetric::kRelative;
  const LevelStudy sky = MeasureLevels("sky", MakeSky(64), *basis, normals, kDefaultMaxLevelError, 2, kRelative);
  EXPECT_EQ(sky.rows[sky.first_over_one_percent].size, 8);
  const LevelStudy spot = MeasureLevels("spot", MakeSpot(64), *basis, normals, kDefaultMaxLevelError, 2, kRelative);
  EXPECT_EQ(spot.rows[spot.first_over_one_percent].size, 32);
  const LevelStudy constant =
      MeasureLevels("constant", MakeConstant(64), *basis, normals, kDefaultMaxLevelError, 2, kRelative);
  EXPECT_EQ(constant.first_over_one_percent, -1);
  EXPECT_EQ(constant.picked, 6);  // 1 x 1 loses nothing
}

// The pick meets 0.5 % on every built-in and the next coarser level would not, at two face sizes, in
// every error metric (the default, peak, first).
TEST(StabilityTest, MaxErrorPickIsRightOnEveryBuiltin) {
  const std::vector<glm::dvec3> normals = SphereNormals(kNormals);
  for (ErrorMetric metric : {kDefaultErrorMetric, ErrorMetric::kRms, ErrorMetric::kRelative}) {
    SCOPED_TRACE(ErrorMetricName(metric));
    for (int size : {64, 128}) {
      if (size == 128 && metric == ErrorMetric::kRms) continue;  // (test time: RMS at 64 only)
      const std::optional<BasisPyramid> basis = BuildBasisPyramid(size);
      ASSERT_TRUE(basis);
      for (const std::string& name : BuiltinEnvironmentNames()) {
        const LevelStudy study = MeasureLevels(name, *MakeBuiltinEnvironment(name, size), *basis, normals,
                                               kDefaultMaxLevelError, 2, metric);
        EXPECT_TRUE(study.pick_meets) << name << " at " << size;
        // The gradient's level errors grow fourfold per level, so the true error of the next coarser
        // level is 4/3 of its difference while the estimate is 1.4 times it: that level may still
        // meet E with an estimate just above it (the pick is safe, one level finer than it might be).
        // The factor 1.4 was fitted on relative errors; in peak and RMS terms it is safe too but not
        // always tight (measured: the studio and the spot at 64 and 128 in peak, the spot at 128 in
        // RMS could have gone one level coarser), so tightness is asserted for the relative metric.
        if (name != "gradient" && metric == ErrorMetric::kRelative) {
          EXPECT_TRUE(study.coarser_fails) << name << " at " << size;
        }
        // The (program, level) pick meets the target against order 2 at level 0, too.
        EXPECT_TRUE(study.program_meets) << name << " at " << size << ": " << study.program_error;
        EXPECT_EQ(study.pair_errors.size(), study.pairs.size());
      }
    }
  }
}

TEST(StabilityTest, SmallSpotsAtCoarseLevelsAreWorstAtEdgesAndCorners) {
  const std::optional<BasisPyramid> basis = BuildBasisPyramid(64);
  ASSERT_TRUE(basis);
  const std::vector<SpotPlacementRow> rows = MeasureSpotPlacement(1.0, *basis, SphereNormals(kNormals));
  // At 2 x 2 a block is a quarter face: measured centre 426 %, edge 1178 %, corner 1704 %.
  const SpotPlacementRow& two = rows[rows.size() - 2];
  ASSERT_EQ(two.size, 2);
  EXPECT_GT(two.face_edge, 2.0 * two.face_centre);
  EXPECT_GT(two.cube_corner, 2.0 * two.face_centre);
  // While blocks are small the centre is worse (its texels are the largest): measured at 32 x 32
  // 4.8 % centre against 1.9 % corner.
  EXPECT_GT(rows[1].face_centre, rows[1].cube_corner);
}

// ---- Finding 3: precision ---------------------------------------------------------------------------

TEST(StabilityTest, FloatSumsLoseTheSkyAsFacesGrow) {
  const std::vector<glm::dvec3> normals = SphereNormals(kNormals);
  // Measured: irradiance error 0.07 % at 256 (116 % at 2048); with a 1e6 sun 18.6 % at 256.
  const AccumulationPrecision small = MeasureFloatAccumulation(MakeSky(64), normals);
  const AccumulationPrecision large = MeasureFloatAccumulation(MakeSky(256), normals);
  EXPECT_GT(large.irradiance_error, 4.0 * small.irradiance_error);
  EXPECT_GT(large.irradiance_error, 1e-4);
  const AccumulationPrecision hdr = MeasureFloatAccumulation(MakeHdrSky(256, 1e6), normals);
  EXPECT_GT(hdr.irradiance_error, 0.05);
}

TEST(StabilityTest, ProgramsDifferOffTheSphereByTheL20Term) {
  const Sh9Rgb sky = ProjectDirect(MakeSky(kFaceSize));
  const std::vector<glm::dvec3> normals = SphereNormals(kNormals);
  const std::vector<double> lengths = {1.0, 1.1, 0.5};
  const Result<ProgramPrecision> measured = MeasureNormalLengths(sky, normals, lengths);
  ASSERT_TRUE(measured) << measured.message();
  const ProgramPrecision& result = *measured;
  ASSERT_EQ(result.lengths.size(), 3u);
  EXPECT_LT(result.lengths[0].paper_error, 1e-6);
  EXPECT_LT(result.lengths[0].unit10_error, 1e-6);
  double peak = 0.0;
  double l20 = 0.0;
  for (const glm::dvec3& n : normals) peak = std::max(peak, std::max({IrradianceEq7(sky, n).x, IrradianceEq7(sky, n).y, IrradianceEq7(sky, n).z}));
  for (int c = 0; c < 3; ++c) l20 = std::max(l20, std::abs(3.0 * kShC3 * sky.at(2, 0)[c]));
  for (const NormalLengthRow& row : result.lengths) {
    // paper - unit10 = 3 c3 L20 (L^2 - 1), in float.
    EXPECT_NEAR(row.programs_difference, l20 * std::abs(row.length * row.length - 1.0) / peak, 1e-6) << row.length;
  }
  // 10 % too long a normal costs about 7 % of the peak in either program (measured 7.4 %, 6.8 %).
  EXPECT_GT(result.lengths[1].paper_error, 0.05);
  EXPECT_GT(result.lengths[1].unit10_error, 0.05);
  // The zero vector: the constant terms, finite.
  EXPECT_TRUE(result.zero_normal.finite);
  const glm::dvec3 mean = kShC0 * sky.at(0, 0);
  EXPECT_NEAR(result.zero_normal.paper.x, (mean.x - kShC3 * sky.at(2, 0).x) / mean.x, 1e-6);
  EXPECT_NEAR(result.zero_normal.unit10.x, (mean.x + 2.0 * kShC3 * sky.at(2, 0).x) / mean.x, 1e-6);
}

TEST(StabilityTest, DenormalConstantsAreKeptNotFlushed) {
  const Sh9Rgb sky = ProjectDirect(MakeSky(kFaceSize));
  const std::vector<double> scales = {1.0, 1e-40, 1e-43};
  const Result<std::vector<ScaledRun>> measured = MeasureScaledRuns(sky, SphereNormals(kNormals), scales);
  ASSERT_TRUE(measured) << measured.message();
  const std::vector<ScaledRun>& runs = *measured;
  EXPECT_FALSE(runs[0].constants_denormal);
  EXPECT_LT(runs[0].batch_error, 1e-5);
  // Denormal constants keep gradual underflow: measured 0.012 % at 1e-40 (a flush to zero would
  // give 100 %), 8.7 % at 1e-43 where only a few mantissa bits are left.
  EXPECT_TRUE(runs[1].constants_denormal);
  EXPECT_LT(runs[1].batch_error, 1e-3);
  EXPECT_GT(runs[2].batch_error, 1e-2);
  EXPECT_LT(runs[2].batch_error, 0.5);
  for (const ScaledRun& run : runs) EXPECT_TRUE(run.engines_identical) << run.scale;
}

TEST(StabilityTest, HdrSunKeepsFloatPrecisionInTheProgram) {
  const Result<HdrResult> measured = MeasureHdrSky(kFaceSize, 1e6, SphereNormals(kNormals), 2);
  ASSERT_TRUE(measured) << measured.message();
  const HdrResult& hdr = *measured;
  EXPECT_GT(hdr.peak_irradiance, 100.0);
  EXPECT_LT(hdr.program_error, 1e-6);  // measured 1.1e-7 of the peak: float rounding only
}

TEST(StabilityTest, ABlackEnvironmentStaysExactlyZero) {
  const Result<ZeroEnvironmentResult> measured = MeasureZeroEnvironment(16, SphereNormals(kNormals));
  ASSERT_TRUE(measured) << measured.message();
  const ZeroEnvironmentResult& zero = *measured;
  EXPECT_TRUE(zero.coefficients_zero);
  EXPECT_TRUE(zero.program_zero);
  EXPECT_TRUE(zero.error_stats_finite);
  EXPECT_EQ(zero.dering_lambda, 0.0);
  EXPECT_EQ(zero.picked_level, 4);  // 1 x 1 of a 16 face
}

// ---- irrmap options and the report ----------------------------------------------------------------

class StabilityFiles : public testing::Test {
 protected:
  void SetUp() override {
    folder_ = fs::path(testing::TempDir()) /
              fmt::format("stability_test_{}_{}", testing::UnitTest::GetInstance()->current_test_info()->name(),
                          std::random_device{}());
    fs::remove_all(folder_);
  }
  void TearDown() override { fs::remove_all(folder_); }
  fs::path folder_;
};

TEST_F(StabilityFiles, IrrmapRecordsTheWindowAndPicksByMaxError) {
  IrrmapOptions options;
  options.environment = "spot";
  options.face_size = 32;
  options.window = ShWindow::kDering;
  options.out_dir = folder_;
  options.error_normals = 200;
  options.sphere_diameter = 32;
  options.map_size = 8;
  options.threads = 2;
  IrrmapReport report;
  ASSERT_EQ(RunIrrmap(options, report).message(), "");
  std::vector<double> estimated;
  for (const LevelReport& level : report.levels) estimated.push_back(level.estimated_error);
  EXPECT_EQ(report.level, CoarsestLevelWithin(estimated, kDefaultMaxLevelError));
  std::ifstream in(folder_ / "coeffs.json");
  const nlohmann::json json = nlohmann::json::parse(in);
  EXPECT_EQ(json["window"]["name"], "dering");
  EXPECT_EQ(json["level_choice"], "max_error");
  EXPECT_LT(json["window"]["factors"][2].get<double>(), 0.5);
  // The windowed coefficients are what was written.
  EXPECT_DOUBLE_EQ(json["coefficients"][8][0].get<double>(), report.coefficients.at(2, 2).x);

  options.window = ShWindow::kNone;
  options.max_error = 0.0;
  ASSERT_FALSE(RunIrrmap(options, report).ok());
}

TEST_F(StabilityFiles, ReportWritesMarkdownWithItsCharts) {
  StabilityOptions options;
  options.face_size = 16;
  options.precision_face_size = 16;
  options.error_normals = 64;
  options.radii = {90.0, 2.0};
  options.threads = 2;
  options.out_dir = folder_;
  StabilityReport report;
  ASSERT_EQ(RunStability(options, report).message(), "");
  std::vector<fs::path> written;
  ASSERT_EQ(WriteStabilityReport(report, written).message(), "");
  for (const char* name : {"stability.md", "sweep.png", "ringing.png", "levels.png"}) {
    EXPECT_TRUE(fs::exists(folder_ / name)) << name;
  }
  std::ifstream in(folder_ / "stability.md");
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_THAT(text.str(), HasSubstr("![max and mean error against light size](sweep.png)"));
  EXPECT_THAT(text.str(), HasSubstr("## 3. Precision"));
  options.radii = {2.0, 90.0};
  EXPECT_FALSE(RunStability(options, report).ok());  // largest first
}

}  // namespace
}  // namespace vs11::irradiance
