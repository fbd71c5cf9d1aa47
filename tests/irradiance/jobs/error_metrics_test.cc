// The error metrics as the literature states them (issue 22 section 1): the peak error
// max |E - E*| / max E* and the RMS error over the mean irradiance, per channel and for luminance,
// checked against a closed form through the whole irrmap job.
//
// The closed form. One directional light of intensity I along l: E(n) = I max(c, 0), c = n . l.
// Nine terms keep Legendre bands 0-2 of max(c, 0) (coefficient (2l + 1)/2 int_-1^1 max(c, 0) P_l):
// 1/4 P0 + 1/2 P1 + 5/16 P2, that is E9(c) / I = 3/32 + c/2 + 15 c^2 / 32. The error
//   d(c) = E9(c) / I - max(c, 0) = 3/32 - |c|/2 + 15 c^2 / 32
// is even in c, so
//   d(0) = 3/32 = 9.375 % of the peak at the horizon, the largest |d| (d is a parabola in |c| on
//     [0, 1] with d(0) = 3/32, d(1) = 1/16 and its minimum inside);
//   d(+-1) = 1/16 = +6.25 % at the light (and opposite it, where the truth is 0);
//   d' = 0 at |c| = 8/15, where d = 3/32 - 4/15 + 2/15 = -19/480 = -3.96 % of the peak: 57.8 degrees
//     from the light and 122.2 degrees from it (there the nine terms give negative irradiance);
//   over the sphere c is uniform in [-1, 1]: mean E = I/4 and mean d^2 = int_0^1 d^2 dc = 1/768
//     (also = mean E^2 - mean E9^2 = 128/768 - 127/768, since E9 is E's least-squares fit), so the
//     RMS error over the mean is sqrt(1/768) / (1/4) = 1 / (4 sqrt 3) = 14.43 %.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "irradiance/io/cube_map.h"
#include "irradiance/io/environments.h"
#include "irradiance/jobs/irrmap_job.h"
#include "irradiance/report/speed_accuracy.h"
#include "irradiance/sh/ground_truth.h"
#include "irradiance/sh/level_choice.h"
#include "irradiance/sh/sh9.h"
#include "irradiance/sh/sh_projection.h"

namespace vs11::irradiance {
namespace {

constexpr double kHorizonError = 3.0 / 32.0;
constexpr double kErrorAtTheLight = 1.0 / 16.0;
constexpr double kLowestError = -19.0 / 480.0;
const double kLowestCosine = 8.0 / 15.0;
const double kRmsOverMean = 1.0 / (4.0 * std::sqrt(3.0));
// The program computes in float and its constants are floats: 1e-5 of the peak covers their
// rounding (kProgramRelativeTolerance of irrmap_job_test.cc).
constexpr double kFloatProgram = 1e-5;

double Nine(double c) { return 3.0 / 32.0 + c / 2.0 + 15.0 * c * c / 32.0; }
double ClampedCosine(double c) { return std::max(c, 0.0); }

// A cube of black texels but one, of radiance kRadiance on +y at (kX, kY): a point light for both the
// projection (level 0 weighs each texel by the basis at its centre times its solid angle) and the
// ground truth (each texel a direction at its centre), so the light's size enters neither, and the
// figures below depend only on where the normals fall and on float rounding.
constexpr int kFace = 32;
constexpr int kX = 11;
constexpr int kY = 20;
constexpr float kRadiance = 1000.0f;

class PointLight : public testing::Test {
 protected:
  static void SetUpTestSuite() {
    CubeMap cube(kFace);
    cube.faces[static_cast<int>(CubeFace::kPositiveY)].at(kX, kY) = glm::vec3(kRadiance);
    IrrmapOptions options;
    options.cube = std::move(cube);
    options.environment = "one bright texel";
    options.level = 0;
    options.write_files = false;
    options.threads = 2;
    options.map_size = 32;
    options.sphere_diameter = 32;
    report_ = new IrrmapReport;
    ASSERT_EQ(RunIrrmap(options, *report_).message(), "");
  }
  static void TearDownTestSuite() {
    delete report_;
    report_ = nullptr;
  }

  static glm::dvec3 Light() { return TexelDirection(CubeFace::kPositiveY, kX, kY, kFace); }
  static double Intensity() { return kRadiance * TexelSolidAngle(kX, kY, kFace); }

  static IrrmapReport* report_;
};
IrrmapReport* PointLight::report_ = nullptr;

TEST_F(PointLight, PeakErrorIsThreeThirtySecondsAtTheHorizon) {
  const ErrorStats& error = report_->levels[0].error;
  const std::vector<glm::dvec3> normals = SphereNormals(kDefaultErrorNormals);
  // The closed form at the job's own normals: the largest |d| over the largest E* among them (the
  // normal nearest the light, whose cosine is a little under 1), and how near they come to the
  // horizon.
  double largest_error = 0.0;
  double peak = 0.0;
  double nearest_horizon = 1.0;
  for (const glm::dvec3& n : normals) {
    const double c = glm::dot(n, Light());
    largest_error = std::max(largest_error, std::abs(Nine(c) - ClampedCosine(c)));
    peak = std::max(peak, ClampedCosine(c));
    nearest_horizon = std::min(nearest_horizon, std::abs(c));
  }
  EXPECT_NEAR(error.max_peak, largest_error / peak, kFloatProgram);
  // d falls off the horizon with slope 1/2: the normals nearest it see 3/32 less half their |c|;
  // the peak among the normals is under I by 1 - peak.
  EXPECT_NEAR(error.max_peak, kHorizonError,
              0.5 * nearest_horizon + kHorizonError * (1.0 / peak - 1.0) + kFloatProgram);
  EXPECT_LT(std::abs(glm::dot(normals[error.worst_peak_index], Light())), 0.05);
  // A white light: every channel and the luminance alike.
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(error.peak_rgb[c], error.max_peak, 1e-9);
  EXPECT_NEAR(error.peak_luminance, error.max_peak, kFloatProgram);
}

TEST_F(PointLight, RmsErrorOverTheMeanIsOneOverFourRootThree) {
  const ErrorStats& error = report_->levels[0].error;
  const std::vector<glm::dvec3> normals = SphereNormals(kDefaultErrorNormals);
  double sum_squares = 0.0;
  double sum = 0.0;
  for (const glm::dvec3& n : normals) {
    const double c = glm::dot(n, Light());
    sum_squares += (Nine(c) - ClampedCosine(c)) * (Nine(c) - ClampedCosine(c));
    sum += ClampedCosine(c);
  }
  const double count = static_cast<double>(normals.size());
  EXPECT_NEAR(error.max_rms, std::sqrt(sum_squares / count) / (sum / count), kFloatProgram);
  // 2000 evenly spread normals integrate the sphere's means to well under 1 % (measured 0.02 %).
  EXPECT_NEAR(error.max_rms, kRmsOverMean, 0.01 * kRmsOverMean);
  EXPECT_NEAR(error.rms_luminance, error.max_rms, kFloatProgram);
  // The per-normal relative error explodes where the truth is black: on the unlit half it is the
  // nine terms' value over a floor of 1 % of the peak.
  EXPECT_GT(error.max_relative, 5.0);
}

// The irradiance map (irradiance.exr) is the nine terms at every texel: +6.25 % facing the light and
// a dip of -3.96 % of the peak 57.8 and 122.2 degrees away.
TEST_F(PointLight, MapRingsAsTheClosedFormSays) {
  const CubeMap& map = report_->irradiance_map;
  ASSERT_EQ(map.face_size, 32);
  double facing_cosine = -1.0, facing_error = 0.0;
  double lowest_error = 1.0, lowest_cosine = 0.0;
  for (CubeFace face : kAllCubeFaces) {
    for (int y = 0; y < map.face_size; ++y) {
      for (int x = 0; x < map.face_size; ++x) {
        const double c = glm::dot(TexelDirection(face, x, y, map.face_size), Light());
        const double error = map.faces[static_cast<int>(face)].at(x, y).x / Intensity() - ClampedCosine(c);
        ASSERT_NEAR(error, Nine(c) - ClampedCosine(c), kFloatProgram) << CubeFaceName(face) << " " << x << " " << y;
        if (c > facing_cosine) {
          facing_cosine = c;
          facing_error = error;
        }
        if (error < lowest_error) {
          lowest_error = error;
          lowest_cosine = c;
        }
      }
    }
  }
  // d' = 7/16 at c = 1: the texel nearest the light, at cosine facing_cosine, is that much lower.
  EXPECT_NEAR(facing_error, kErrorAtTheLight, 7.0 / 16.0 * (1.0 - facing_cosine) + kFloatProgram);
  // The map's texels lie about 3 degrees apart: the nearest to |c| = 8/15 is within 0.05 of it in c,
  // where the parabola (curvature 15/16) rises by at most 15/32 x 0.05^2 = 1.2e-3.
  EXPECT_GE(lowest_error, kLowestError - kFloatProgram);
  EXPECT_LT(lowest_error, kLowestError + 1.2e-3);
  EXPECT_NEAR(std::abs(lowest_cosine), kLowestCosine, 0.05);
}

// A light of finite size approaches the point light's figures: a round light of radius a spreads the
// horizon's kink over |c| < sin a, so the largest error sits between 3/32 - sin(a)/2 and 3/32; its
// texels (about 1.4 degrees at 64x64) widen a by about a texel's half-diagonal, 1 degree.
TEST(ErrorMetrics, SmallRoundLightApproachesThePointLight) {
  SpotParams spot;
  spot.angular_radius_degrees = 2.0;
  const CubeMap env = MakeSpot(64, spot);
  const std::vector<glm::dvec3> normals = SphereNormals(kDefaultErrorNormals);
  const Sh9Rgb sh = ProjectDirect(env);
  std::vector<glm::dvec3> estimate;
  for (const glm::dvec3& n : normals) estimate.push_back(IrradianceEq7(sh, n));
  const ErrorStats error = CompareIrradiance(estimate, GroundTruthIrradiance(env, normals, 2), normals);
  const double widened = (spot.angular_radius_degrees + 1.0) * std::numbers::pi / 180.0;
  EXPECT_LE(error.max_peak, kHorizonError + kFloatProgram);
  EXPECT_GE(error.max_peak, kHorizonError - std::sin(widened) / 2.0);
  EXPECT_NEAR(error.max_rms, kRmsOverMean, 0.05 * kRmsOverMean);
}

// A constant environment: the nine terms hold it exactly at every level, so what any metric shows is
// the ground truth's own quadrature error at 32x32 (the horizon's kink cuts through texels; 1.4e-4,
// kFurnaceError of irrmap_job_test.cc), and between levels no error at all but float rounding.
TEST(ErrorMetrics, ConstantEnvironmentHasNoErrorInAnyMetric) {
  constexpr double kFurnaceError = 5e-4;
  IrrmapOptions options;
  options.environment = "constant";
  options.face_size = 32;
  options.write_files = false;
  options.threads = 2;
  options.error_normals = 300;
  options.map_size = 8;
  options.sphere_diameter = 32;
  IrrmapReport report;
  ASSERT_EQ(RunIrrmap(options, report).message(), "");
  for (const LevelReport& level : report.levels) {
    const ErrorStats& e = level.error;
    for (double figure : {e.max_relative, e.mean_relative, e.max_peak, e.max_rms, e.peak_luminance, e.rms_luminance}) {
      EXPECT_LT(figure, kFurnaceError) << "level " << level.level;
    }
  }
  // The estimates, in each metric (no ground truth needed): every level the same irradiance.
  options.coefficients_only = true;
  for (ErrorMetric metric : kAllErrorMetrics) {
    options.error_metric = metric;
    ASSERT_EQ(RunIrrmap(options, report).message(), "");
    for (const LevelReport& level : report.levels) {
      EXPECT_LT(level.estimated_error, 1e-6) << ErrorMetricName(metric) << " level " << level.level;
    }
    EXPECT_EQ(report.level, static_cast<int>(report.levels.size()) - 1);  // 1x1 loses nothing
  }
}

// The definitions on numbers worked by hand: two samples, three channels, one of them black.
TEST(ErrorMetrics, PeakAndRmsFollowTheirDefinitionsPerChannelAndForLuminance) {
  const std::vector<glm::dvec3> truth = {{2.0, 1.0, 0.0}, {1.0, 1.0, 0.0}};
  const std::vector<glm::dvec3> estimate = {{2.2, 1.0, 0.0}, {1.0, 0.5, 0.0}};
  const ErrorStats e = CompareIrradiance(estimate, truth);
  EXPECT_NEAR(e.peak_rgb.r, 0.2 / 2.0, 1e-12);                        // max |d| 0.2, peak 2
  EXPECT_NEAR(e.peak_rgb.g, 0.5 / 1.0, 1e-12);                        // max |d| 0.5, peak 1
  EXPECT_EQ(e.peak_rgb.b, 0.0);                                       // black and exact: 0
  EXPECT_NEAR(e.rms_rgb.r, std::sqrt(0.04 / 2.0) / 1.5, 1e-12);       // mean 1.5
  EXPECT_NEAR(e.rms_rgb.g, std::sqrt(0.25 / 2.0) / 1.0, 1e-12);
  const double y0 = 0.2126 * 2.0 + 0.7152 + 0.0 * 0.0722, y1 = 0.2126 + 0.7152;
  const double d0 = 0.2126 * 0.2, d1 = 0.7152 * 0.5;
  EXPECT_NEAR(e.peak_luminance, d1 / y0, 1e-12);
  EXPECT_NEAR(e.rms_luminance, std::sqrt((d0 * d0 + d1 * d1) / 2.0) / ((y0 + y1) / 2.0), 1e-12);
  EXPECT_NEAR(e.max_peak, 0.5, 1e-12);
  EXPECT_NEAR(e.max_rms, std::sqrt(0.125), 1e-12);
  EXPECT_EQ(e.worst_peak_index, 1u);
  EXPECT_EQ(ErrorFigure(e, ErrorMetric::kPeak), e.max_peak);
  EXPECT_EQ(ErrorFigure(e, ErrorMetric::kRms), e.max_rms);
  EXPECT_EQ(ErrorFigure(e, ErrorMetric::kRelative), e.max_relative);
  // Light where the truth is black: no finite fraction of a zero peak.
  const std::vector<glm::dvec3> lit = {{2.2, 1.0, 0.1}, {1.0, 0.5, 0.0}};
  EXPECT_TRUE(std::isinf(CompareIrradiance(lit, truth).peak_rgb.b));
}

TEST(ErrorMetrics, NamesParseBack) {
  for (ErrorMetric metric : kAllErrorMetrics) EXPECT_EQ(kErrorMetricNames.Find(ErrorMetricName(metric)), metric);
  EXPECT_EQ(kErrorMetricNames.Find("max"), std::nullopt);
  EXPECT_EQ(kErrorMetricNames.List(), "relative, peak or rms");
  EXPECT_EQ(kDefaultErrorMetric, ErrorMetric::kPeak);
}

// Issue 22 section 4: one run used to print two errors for the same level, the table's over 2000
// normals and the preview's over the sphere's pixels. Now the table, coeffs.json, the preview's
// captions and the chart state the same figures for the same level. The spot: the environment whose
// relative error differs most between the two sets of normals (all of it on the unlit side).
TEST(SameFigure, TableCoeffsJsonPreviewAndChartAgreeForEachLevel) {
  const std::filesystem::path folder = std::filesystem::path(testing::TempDir()) /
                                       fmt::format("vs11_same_figure_{}", std::random_device{}());
  IrrmapOptions options;
  options.environment = "spot";
  options.face_size = 32;
  options.out_dir = folder;
  options.threads = 2;
  options.map_size = 8;
  options.sphere_diameter = 64;
  IrrmapReport report;
  ASSERT_EQ(RunIrrmap(options, report).message(), "");
  std::ifstream file(folder / "coeffs.json");
  const nlohmann::json json = nlohmann::json::parse(file);
  EXPECT_EQ(json["error_metric"], "peak");
  std::istringstream table(FormatLevelTable(report));
  std::string line;
  std::getline(table, line);  // the header
  for (const LevelReport& level : report.levels) {
    const nlohmann::json& row = json["levels"][level.level];
    EXPECT_DOUBLE_EQ(row["peak_error"].get<double>(), level.error.max_peak);
    EXPECT_DOUBLE_EQ(row["rms_error"].get<double>(), level.error.max_rms);
    EXPECT_DOUBLE_EQ(row["max_relative_error"].get<double>(), level.error.max_relative);
    EXPECT_DOUBLE_EQ(row["peak_error_channels"]["luminance"].get<double>(), level.error.peak_luminance);
    ASSERT_TRUE(std::getline(table, line));
    EXPECT_THAT(line, testing::HasSubstr(fmt::format("{:.3f} %", 100.0 * level.error.max_peak)));
    EXPECT_THAT(line, testing::HasSubstr(fmt::format("{:.3f} %", 100.0 * level.error.max_rms)));
  }
  // The preview: every panel's caption is its level's peak and RMS (the chosen reduced program's,
  // for its own panel), to the 3 digits it prints.
  ASSERT_FALSE(report.preview_panels.empty());
  for (const IrrmapReport::PreviewPanelText& panel : report.preview_panels) {
    int size = 0;
    const ErrorStats& error =
        std::sscanf(panel.label.c_str(), "SH9 from %dx", &size) == 1
            ? report.levels[std::countr_zero(static_cast<unsigned>(options.face_size / size))].error
            : report.program_error;
    double peak = 0.0, rms = 0.0;
    ASSERT_EQ(std::sscanf(panel.caption.c_str(), "peak %lf%%, rms %lf%%", &peak, &rms), 2) << panel.caption;
    EXPECT_NEAR(peak, 100.0 * error.max_peak, 5e-3 * peak) << panel.label;
    EXPECT_NEAR(rms, 100.0 * error.max_rms, 5e-3 * rms) << panel.label;
  }
  // The chart: the same normals, program and truth (its batch engine gives the jit's bits).
  SpeedAccuracyOptions chart;
  chart.environments = {"spot"};
  chart.face_size = options.face_size;
  chart.threads = 2;
  chart.min_batch_ms = 0.0;
  chart.batches = 1;
  SpeedAccuracyResult sweep;
  ASSERT_EQ(RunSpeedAccuracySweep(chart, sweep).message(), "");
  int compared = 0;
  for (const SpeedAccuracyPoint& point : sweep.points) {
    if (point.method != ProjectionMethod::kMipPyramid || point.order != ShOrder::kOrder2) continue;
    EXPECT_DOUBLE_EQ(point.error.max_peak, report.levels[point.level].error.max_peak) << point.level;
    EXPECT_DOUBLE_EQ(point.error.max_rms, report.levels[point.level].error.max_rms) << point.level;
    EXPECT_DOUBLE_EQ(point.error.mean_relative, report.levels[point.level].error.mean_relative) << point.level;
    ++compared;
  }
  EXPECT_EQ(compared, static_cast<int>(report.levels.size()));
  std::filesystem::remove_all(folder);
}

}  // namespace
}  // namespace vs11::irradiance
