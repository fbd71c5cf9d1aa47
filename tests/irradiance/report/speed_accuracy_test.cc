#include "irradiance/report/speed_accuracy.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "irradiance/sh/sh_projection.h"

namespace vs11::irradiance {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::StartsWith;

constexpr int kFaceSize = 8;  // levels 0..3
// A grey environment gives exactly L00 at every level of both methods, up to float storage of the
// radiance and the basis weights and the float arithmetic of the vertex program, so every level's
// error is the same (it is the ground truth's own: brute force over 8 x 8 faces is not exactly pi).
constexpr double kWhiteFurnaceRelative = 1e-5;

SpeedAccuracyOptions FastOptions(std::vector<std::string> environments) {
  SpeedAccuracyOptions options;
  options.environments = std::move(environments);
  options.face_size = kFaceSize;
  options.error_normals = 64;
  options.threads = 1;
  options.min_batch_ms = 0.0;
  options.batches = 1;
  return options;
}

const SpeedAccuracyPoint& Find(const SpeedAccuracyResult& result, std::string_view environment,
                               ProjectionMethod method, int level, ShOrder order = ShOrder::kOrder2) {
  const auto it = std::find_if(result.points.begin(), result.points.end(), [&](const SpeedAccuracyPoint& p) {
    return p.environment == environment && p.method == method && p.level == level && p.order == order;
  });
  if (it != result.points.end()) return *it;
  ADD_FAILURE() << "no point for " << environment << " level " << level;
  // A point whose errors are NaN: every comparison the caller makes with it fails too.
  static const SpeedAccuracyPoint missing = [] {
    SpeedAccuracyPoint point;
    point.error.max_relative = point.error.mean_relative = std::numeric_limits<double>::quiet_NaN();
    point.error.max_peak = point.error.max_rms = std::numeric_limits<double>::quiet_NaN();
    return point;
  }();
  return missing;
}

TEST(SpeedAccuracy, SweepsEveryLevelOfEachMethodForEachEnvironment) {
  SpeedAccuracyResult result;
  ASSERT_EQ(RunSpeedAccuracySweep(FastOptions({"constant", "sky"}), result).message(), "");
  const int levels = LevelCount(kFaceSize);
  // Per environment: every direct level, and every mip level with each of the four programs.
  ASSERT_EQ(result.points.size(), static_cast<std::size_t>(2 * (1 + 4) * levels));
  ASSERT_EQ(result.environments.size(), 2u);
  for (const SpeedAccuracyPoint& point : result.points) {
    EXPECT_EQ(point.size, kFaceSize >> point.level);
    EXPECT_GT(point.update_ms, 0.0);
  }
  const double furnace_error = Find(result, "constant", ProjectionMethod::kMipPyramid, 0).error.max_relative;
  EXPECT_LT(furnace_error, 0.01);
  for (int level = 0; level < levels; ++level) {
    for (ProjectionMethod method : kAllProjectionMethods) {
      EXPECT_NEAR(Find(result, "constant", method, level).error.max_relative, furnace_error, kWhiteFurnaceRelative);
    }
  }
  // At level 0 both methods are the full-resolution projection.
  EXPECT_NEAR(Find(result, "sky", ProjectionMethod::kMipPyramid, 0).error.mean_relative,
              Find(result, "sky", ProjectionMethod::kDirectOnLevel, 0).error.mean_relative, 1e-6);
  // The order dimension: the constant environment is exact with one slot; the sky needs band 2.
  EXPECT_NEAR(Find(result, "constant", ProjectionMethod::kMipPyramid, 0, ShOrder::kOrder0).error.max_relative,
              furnace_error, kWhiteFurnaceRelative);
  EXPECT_GT(Find(result, "sky", ProjectionMethod::kMipPyramid, 0, ShOrder::kOrder1).error.mean_relative,
            Find(result, "sky", ProjectionMethod::kMipPyramid, 0).error.mean_relative);
  // Six texels cannot hold the sky's sun: the 1 x 1 level is far worse than full resolution.
  EXPECT_GT(Find(result, "sky", ProjectionMethod::kMipPyramid, levels - 1).error.mean_relative,
            2.0 * Find(result, "sky", ProjectionMethod::kMipPyramid, 0).error.mean_relative);
}

TEST(SpeedAccuracy, CsvHasAHeaderAndOneLinePerPoint) {
  SpeedAccuracyResult result;
  ASSERT_EQ(RunSpeedAccuracySweep(FastOptions({"spot"}), result).message(), "");
  const std::string csv = SpeedAccuracyCsv(result);
  // The old columns first, peak_error and rms_error added at the end.
  EXPECT_THAT(csv, StartsWith("environment,method,level,size,update_ms,mips_ms,mean_relative_error,"
                              "max_relative_error,order,slots,peak_error,rms_error\n"));
  EXPECT_THAT(csv, HasSubstr("\nspot,mip,0,8,"));
  EXPECT_THAT(csv, HasSubstr(",zh3,6,"));
  const SpeedAccuracyPoint& point = Find(result, "spot", ProjectionMethod::kDirectOnLevel, 3);
  EXPECT_THAT(csv, HasSubstr(fmt::format(",order2,11,{:.6g},{:.6g}\n", point.error.max_peak, point.error.max_rms)));
  EXPECT_EQ(static_cast<std::size_t>(std::count(csv.begin(), csv.end(), '\n')), result.points.size() + 1);
  EXPECT_THAT(csv, HasSubstr("\nspot,direct,3,1,"));
}

TEST(SpeedAccuracy, ChartHasOneSolidAndOneDashedCurvePerEnvironment) {
  SpeedAccuracyResult result;
  ASSERT_EQ(RunSpeedAccuracySweep(FastOptions({"sky", "studio"}), result).message(), "");
  const GnuplotChart chart = SpeedAccuracyChart(result);
  EXPECT_THAT(chart.script, HasSubstr("set logscale xy"));
  EXPECT_THAT(chart.script, HasSubstr("'sky (mip pyramid)'"));
  EXPECT_THAT(chart.script, HasSubstr("'studio (direct on level)'"));
  EXPECT_THAT(chart.script, HasSubstr("with labels"));
  EXPECT_THAT(chart.script, HasSubstr("index 3 using"));
  // The order panel: one curve per environment from full resolution (8x8 faces have no 16x16 level).
  EXPECT_THAT(chart.script, HasSubstr("set multiplot layout 1,2"));
  EXPECT_THAT(chart.script, HasSubstr("'studio from 8x8'"));
  EXPECT_THAT(chart.script, HasSubstr("index 5 using"));
  EXPECT_THAT(chart.script, Not(HasSubstr("index 6 using")));
}

TEST(SpeedAccuracy, WritesCsvSvgAndPngAndNothingElse) {
  SpeedAccuracyResult result;
  ASSERT_EQ(RunSpeedAccuracySweep(FastOptions({"sky"}), result).message(), "");
  const fs::path folder = fs::path(::testing::TempDir()) / "vs11_speed_accuracy_write";
  fs::remove_all(folder);
  std::vector<fs::path> written;
  ASSERT_EQ(WriteSpeedAccuracy(result, folder / "nested", written).message(), "");
  EXPECT_EQ(written.size(), 3u);
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(folder / "nested")) names.push_back(entry.path().filename());
  std::sort(names.begin(), names.end());
  EXPECT_THAT(names, ::testing::ElementsAre("speed_accuracy.csv", "speed_accuracy.png", "speed_accuracy.svg"));
  std::ifstream svg(folder / "nested" / "speed_accuracy.svg");
  EXPECT_THAT(std::string(std::istreambuf_iterator<char>(svg), {}), HasSubstr("<svg"));
  fs::remove_all(folder);
}

TEST(SpeedAccuracy, RejectsBadOptionsAndUnknownEnvironments) {
  SpeedAccuracyResult result;
  SpeedAccuracyOptions options = FastOptions({"sky"});
  options.face_size = 6;
  EXPECT_THAT(RunSpeedAccuracySweep(options, result).message(), HasSubstr("power of two"));
  options = FastOptions({"no_such_environment.exr"});
  EXPECT_FALSE(RunSpeedAccuracySweep(options, result).ok());
  options = FastOptions({"sky"});
  options.batches = 0;
  EXPECT_THAT(RunSpeedAccuracySweep(options, result).message(), HasSubstr("--batches"));
}

// A file's curves are named by its base name, and gnuplot's enhanced text must not read its
// underscore as a subscript ("probulator" with a small "g" under it): in the script, escaped, and in
// the SVG gnuplot draws from it, the name as written.
TEST(SpeedAccuracy, CurvesAreNamedByTheFilesBaseNameAsWritten) {
  SpeedAccuracyResult result;
  const std::string path = "/data/light_probes/probulator_grace.hdr";
  result.environments = {{path, 16, 1.0}};
  for (ProjectionMethod method : kAllProjectionMethods) {
    for (int level = 0; level < 3; ++level) {
      SpeedAccuracyPoint point{path, method, level, 16 >> level, ShOrder::kOrder2, 0.1 * (level + 1), {}};
      point.error.max_peak = point.error.mean_relative = 0.01 * (level + 1);
      result.points.push_back(point);
    }
  }
  const GnuplotChart chart = SpeedAccuracyChart(result);
  EXPECT_THAT(chart.script, HasSubstr("title 'probulator\\_grace.hdr (mip pyramid)'"));
  EXPECT_THAT(chart.script, HasSubstr("title 'probulator\\_grace.hdr (direct on level)'"));
  EXPECT_THAT(chart.script, HasSubstr("title 'probulator\\_grace.hdr from 16x16'"));
  EXPECT_THAT(chart.script, Not(HasSubstr("light_probes")));
  EXPECT_EQ(GnuplotLiteral("a_b^c{d}@e&f~g\\h'i"), "'a\\_b\\^c\\{d\\}\\@e\\&f\\~g\\\\h''i'");

  const fs::path folder = fs::path(::testing::TempDir()) / "vs11_speed_accuracy_labels";
  fs::remove_all(folder);
  fs::create_directories(folder);
  ASSERT_EQ(RenderGnuplotChart(chart, {folder / "chart.svg"}).message(), "");
  std::ifstream svg(folder / "chart.svg");
  const std::string text(std::istreambuf_iterator<char>(svg), {});
  EXPECT_THAT(text, HasSubstr(">probulator_grace.hdr (mip pyramid)<"));
  EXPECT_THAT(text, HasSubstr(">probulator_grace.hdr from 16x16<"));
  fs::remove_all(folder);
}

// The axis shows the figure --error-metric names, the same as irrmap's level table for that level;
// the CSV carries every figure, its old columns first.
TEST(SpeedAccuracy, AxisFollowsTheErrorMetricAndTheCsvAddsPeakAndRms) {
  SpeedAccuracyOptions options = FastOptions({"spot"});
  for (ErrorMetric metric : kAllErrorMetrics) {
    options.error_metric = metric;
    SpeedAccuracyResult result;
    ASSERT_EQ(RunSpeedAccuracySweep(options, result).message(), "");
    EXPECT_EQ(result.metric, metric);
    const GnuplotChart chart = SpeedAccuracyChart(result);
    const SpeedAccuracyPoint& point = Find(result, "spot", ProjectionMethod::kMipPyramid, 1);
    EXPECT_THAT(chart.data, HasSubstr(fmt::format("{:.6g} {:.6g} 1\n", point.update_ms,
                                                  100.0 * ChartErrorFigure(point.error, metric))));
  }
}

}  // namespace
}  // namespace vs11::irradiance
