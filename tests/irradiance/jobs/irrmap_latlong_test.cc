// irrmap on lat-long maps: projected where they lie, resampled to a cube only for the stages that
// read one (irradiance/jobs/irrmap_environment.h).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "irradiance/io/environment_io.h"
#include "irradiance/jobs/irrmap_job.h"
#include "irradiance/sh/latlong_projection.h"
#include "irradiance/sh/sh_projection.h"

namespace vs11::irradiance {
namespace {

namespace fs = std::filesystem;

// A 256 x 128 panorama: a gradient and a small bright patch.
Image Panorama() {
  Image image(256, 128);
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const bool patch = x >= 90 && x < 96 && y >= 30 && y < 34;
      image.at(x, y) = glm::vec3(0.2f + 0.005f * static_cast<float>(y), 0.5f, patch ? 400.0f : 0.1f);
    }
  }
  return image;
}

bool HasTiming(const IrrmapReport& report, std::string_view name) {
  return std::any_of(report.timings.begin(), report.timings.end(),
                     [&](const Timing& timing) { return timing.name == name; });
}

double LargestDifference(const Sh9Rgb& a, const Sh9Rgb& b) {
  double worst = 0.0, largest = 0.0;
  for (int i = 0; i < kSh9Coefficients; ++i) {
    for (int c = 0; c < 3; ++c) {
      worst = std::max(worst, std::abs(a.coefficients[i][c] - b.coefficients[i][c]));
      largest = std::max(largest, std::abs(b.coefficients[i][c]));
    }
  }
  return worst / largest;
}

class IrrmapLatLong : public testing::Test {
 protected:
  void SetUp() override {
    folder_ = fs::path(testing::TempDir()) / fmt::format("irrmap_latlong_test_{}_{}",
                                                         testing::UnitTest::GetInstance()->current_test_info()->name(),
                                                         std::random_device{}());
    fs::create_directories(folder_);
    file_ = folder_ / "pano.exr";
    ASSERT_EQ(WriteImage(Panorama(), file_), std::nullopt);
    options_.environment = file_.string();
    options_.face_size = 32;
    options_.out_dir = folder_ / "out";
    options_.error_normals = 300;
    options_.sphere_diameter = 32;
    options_.map_size = 16;
    options_.threads = 2;
    options_.window = "none";
  }
  void TearDown() override { fs::remove_all(folder_); }

  fs::path folder_, file_;
  IrrmapOptions options_;
  IrrmapReport report_;
};

TEST_F(IrrmapLatLong, CoefficientsOnlyProjectThePanoramaInPlaceAndBuildNoCube) {
  options_.coefficients_only = true;
  options_.no_ground_truth = true;
  options_.level = 0;
  ASSERT_EQ(RunIrrmap(options_, report_), std::nullopt);
  EXPECT_TRUE(HasTiming(report_, "latlong_pyramid"));
  EXPECT_FALSE(HasTiming(report_, "resample_cube"));
  EXPECT_FALSE(HasTiming(report_, "env_mips"));
  EXPECT_EQ(report_.layout, "latlong");
  EXPECT_EQ(report_.face_size, 32);
  ASSERT_EQ(report_.levels.size(), 6u);
  for (int k = 0; k < 6; ++k) EXPECT_EQ(report_.levels[static_cast<std::size_t>(k)].size, 32 >> k);
  // Level 0 is the panorama's own exact projection, which the cube route approximates.
  EXPECT_LT(LargestDifference(report_.coefficients, ProjectLatLong(Panorama())), 1e-12);
  EXPECT_LT(LargestDifference(report_.coefficients, ProjectDirect(ResampleLatLong(Panorama(), 32))), 2e-3);
}

TEST_F(IrrmapLatLong, TheIrradianceMapNeedsNoCubeButTheGroundTruthResamplesOnce) {
  options_.no_ground_truth = true;
  ASSERT_EQ(RunIrrmap(options_, report_), std::nullopt);
  EXPECT_FALSE(HasTiming(report_, "resample_cube"));
  EXPECT_EQ(report_.irradiance_map.face_size, 16);
  options_.no_ground_truth = false;
  ASSERT_EQ(RunIrrmap(options_, report_), std::nullopt);
  EXPECT_EQ(std::count_if(report_.timings.begin(), report_.timings.end(),
                          [](const Timing& timing) { return timing.name == "resample_cube"; }),
            1);
  EXPECT_TRUE(report_.errors_measured);
  // The nine terms of a smooth panorama against the exact convolution of its cube.
  EXPECT_LT(report_.levels[0].error.max_peak, 0.2);
}

TEST_F(IrrmapLatLong, AnArrayInMemoryGivesWhatItsFileGives) {
  options_.coefficients_only = true;
  ASSERT_EQ(RunIrrmap(options_, report_), std::nullopt);
  const Sh9Rgb from_file = report_.coefficients;
  const int level = report_.level;
  options_.latlong = Panorama();
  options_.environment = "array";
  options_.layout = "latlong";
  ASSERT_EQ(RunIrrmap(options_, report_), std::nullopt);
  EXPECT_EQ(report_.level, level);
  EXPECT_EQ(LargestDifference(report_.coefficients, from_file), 0.0);
}

}  // namespace
}  // namespace vs11::irradiance
