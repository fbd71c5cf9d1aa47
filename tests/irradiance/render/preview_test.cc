#include "irradiance/render/preview.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "irradiance/io/environments.h"
#include "irradiance/report/preview_errors.h"
#include "irradiance/sh/sh9.h"
#include "irradiance/sh/sh_projection.h"

namespace vs11::irradiance {
namespace {

using testing::HasSubstr;

// Unit normals built in double.
constexpr double kUnitTolerance = 1e-12;
// Bilinear interpolation of a quadratic function of the normal on the default 2 x 2.8 degree grid:
// the error is h^2 / 8 times the second derivative, h ~ 0.05 rad, so ~3e-4 for derivatives of ~1.
constexpr double kGridInterpolationError = 1e-3;
// A pixel brighter than this (of 1) counts as drawn.
constexpr float kDrawnThreshold = 0.02f;

// A smooth positive function of the normal, like an irradiance map.
glm::dvec3 SmoothIrradiance(glm::dvec3 n) {
  return glm::dvec3(2.0 + n.x + 0.5 * n.y * n.z, 1.5 + 0.3 * n.z - 0.2 * n.x * n.x, 1.0 + 0.4 * n.y);
}

TEST(Preview, SpherePixelsHaveUnitNormalsFacingTheViewer) {
  const SpherePixels sphere = MakeSpherePixels(64);
  ASSERT_EQ(sphere.pixels.size(), sphere.normals.size());
  ASSERT_EQ(sphere.pixels.size(), sphere.coverage.size());
  // About pi / 4 of the square, plus the half-covered rim.
  EXPECT_NEAR(static_cast<double>(sphere.pixels.size()) / (64 * 64), std::numbers::pi / 4, 0.03);
  for (std::size_t k = 0; k < sphere.normals.size(); ++k) {
    EXPECT_NEAR(glm::length(sphere.normals[k]), 1.0, kUnitTolerance);
    EXPECT_GE(sphere.normals[k].z, 0.0);
    EXPECT_GT(sphere.coverage[k], 0.0f);
    EXPECT_LE(sphere.coverage[k], 1.0f);
  }
}

TEST(Preview, SphereShowsPlusXOnTheViewersLeftAndPlusYUp) {
  const SpherePixels sphere = MakeSpherePixels(65);
  for (std::size_t k = 0; k < sphere.pixels.size(); ++k) {
    const glm::ivec2 p = sphere.pixels[k];
    if (p == glm::ivec2(32, 32)) {
      EXPECT_NEAR(sphere.normals[k].z, 1.0, kUnitTolerance);
    }
    if (p.y == 32 && p.x < 16) {
      EXPECT_GT(sphere.normals[k].x, 0.5);
    }
    if (p.x == 32 && p.y < 16) {
      EXPECT_GT(sphere.normals[k].y, 0.5);
    }
  }
}

TEST(Preview, HemisphereGridInterpolatesASmoothFunctionClosely) {
  HemisphereGrid grid;
  std::vector<glm::dvec3> values;
  for (const glm::dvec3& n : grid.normals()) values.push_back(SmoothIrradiance(n));
  grid.SetValues(values);
  std::mt19937 random(5);
  std::normal_distribution<double> gaussian;
  double worst = 0.0;
  for (int i = 0; i < 2000; ++i) {
    glm::dvec3 n = glm::normalize(glm::dvec3(gaussian(random), gaussian(random), gaussian(random)));
    n.z = std::abs(n.z);
    const glm::dvec3 error = grid.Sample(n) - SmoothIrradiance(n);
    worst = std::max({worst, std::abs(error.x), std::abs(error.y), std::abs(error.z)});
  }
  EXPECT_LT(worst, kGridInterpolationError);
  // Exactly the tabulated value at a grid normal, the pole included.
  EXPECT_NEAR(grid.Sample({0.0, 0.0, 1.0}).x, SmoothIrradiance({0.0, 0.0, 1.0}).x, 1e-12);
}

TEST(Preview, ErrorRampRunsFromViridisPurpleToYellow) {
  const glm::vec3 low = ErrorRamp(0.0);
  const glm::vec3 high = ErrorRamp(1.0);
  EXPECT_GT(low.b, low.g);   // #440154
  EXPECT_GT(high.r, 0.9f);   // #fde725
  EXPECT_GT(high.g, 0.7f);
  EXPECT_EQ(ErrorRamp(-1.0), low);
  EXPECT_EQ(ErrorRamp(2.0), high);
}

class PreviewRender : public testing::Test {
 protected:
  void SetUp() override {
    environment_ = *MakeBuiltinEnvironment("sky", 32);
    options_.sphere_diameter = 48;
    sphere_ = MakeSpherePixels(options_.sphere_diameter);
    const Sh9Rgb sh = ProjectDirect(environment_);
    truth_.label = "exact";
    for (const glm::dvec3& n : sphere_.normals) truth_.irradiance.push_back(IrradianceEq6(sh, n));
  }

  // The truth scaled by `factor`: a relative error of |factor - 1| everywhere.
  PreviewPanel Scaled(double factor) const {
    PreviewPanel panel{"scaled", {}};
    for (const glm::dvec3& e : truth_.irradiance) panel.irradiance.push_back(e * factor);
    return panel;
  }

  CubeMap environment_;
  PreviewOptions options_;
  SpherePixels sphere_;
  PreviewPanel truth_;
};

TEST_F(PreviewRender, ImageHasTheLayoutSizeAndIsNotBlank) {
  const std::vector<PreviewPanel> estimates = {Scaled(1.01), Scaled(0.97)};
  const PreviewResult result = RenderPreview(sphere_, truth_, estimates, AnalysePreviewErrors(truth_, estimates, {}), environment_, options_);
  const PreviewLayout layout = ComputePreviewLayout(3, environment_.face_size, options_);
  EXPECT_EQ(result.image.width, layout.width);
  EXPECT_EQ(result.image.height, layout.height);
  EXPECT_GT(result.image.width, 3 * options_.sphere_diameter + 4 * layout.cross_face);
  EXPECT_GT(result.image.height, 2 * options_.sphere_diameter);
  std::size_t drawn = 0;
  float brightest = 0.0f;
  for (const glm::vec3& p : result.image.pixels) {
    if (std::max({p.r, p.g, p.b}) > kDrawnThreshold) ++drawn;
    brightest = std::max({brightest, p.r, p.g, p.b});
  }
  EXPECT_GT(drawn, result.image.pixels.size() / 5);
  EXPECT_LE(brightest, 1.0f);
  if (std::filesystem::exists(kDefaultPreviewFont)) {
    EXPECT_TRUE(result.warnings.empty());
  }
}

TEST_F(PreviewRender, BrightestSphereIsShownAtTheWhiteLevel) {
  const PreviewResult result = RenderPreview(sphere_, truth_, {}, PreviewErrors{}, environment_, options_);
  // Sphere 0 starts at the left margin (16) below the first label row (font size + 8).
  const int top = 16 + options_.font_size + 8;
  float brightest = 0.0f;
  for (std::size_t k = 0; k < sphere_.pixels.size(); ++k) {
    if (sphere_.coverage[k] < 1.0f) continue;
    const glm::vec3 p = result.image.at(16 + sphere_.pixels[k].x, top + sphere_.pixels[k].y);
    brightest = std::max({brightest, p.r, p.g, p.b});
  }
  EXPECT_NEAR(brightest, kSphereWhite, 0.02);
}

TEST_F(PreviewRender, LongLabelsShrinkIntoTheirColumnsAndNeverOverlap) {
  ASSERT_TRUE(std::filesystem::exists(kDefaultPreviewFont)) << "fonts-dejavu-core (.ci/setup) is needed";
  std::vector<PreviewPanel> estimates;
  for (const char* label : {"SH9 from 256x256", "SH9 from 128x128 (level 1) *", "SH9 from 64x64 (level 2)",
                            "SH9 from 16x16 (level 4)"}) {
    estimates.push_back(Scaled(1.5));  // large errors: "max 50.0%, mean 50.0%" and a 50% ramp
    estimates.back().label = label;
  }
  const PreviewResult result = RenderPreview(sphere_, truth_, estimates, AnalysePreviewErrors(truth_, estimates, {}), environment_, options_);
  ASSERT_TRUE(result.warnings.empty());
  ASSERT_EQ(result.labels.size(), 2 * estimates.size() + 1 + 3 + 1 + 1);  // spheres, errors, ramp, title, environment
  const int pitch = options_.sphere_diameter + 16;  // a column: sphere and margin
  for (std::size_t a = 0; a < result.labels.size(); ++a) {
    const PreviewResult::PlacedLabel& first = result.labels[a];
    for (std::size_t b = a + 1; b < result.labels.size(); ++b) {
      const PreviewResult::PlacedLabel& second = result.labels[b];
      const bool apart = first.right <= second.left || second.right <= first.left || first.bottom <= second.top ||
                         second.bottom <= first.top;
      EXPECT_TRUE(apart) << "'" << first.text << "' overlaps '" << second.text << "'";
    }
  }
  // The chosen level's label, star and all, stays over its own sphere (panel 2), within half the
  // margin either side.
  const auto chosen = std::find_if(result.labels.begin(), result.labels.end(),
                                   [](const auto& label) { return label.text.ends_with("*"); });
  ASSERT_NE(chosen, result.labels.end());
  const int sphere_left = 16 + 2 * pitch;
  EXPECT_GE(chosen->left, sphere_left - 8);
  EXPECT_LE(chosen->right, sphere_left + options_.sphere_diameter + 8);
  EXPECT_LT(chosen->font_size, options_.font_size);  // it did not fit at full size in 48 + 16 pixels
}

TEST_F(PreviewRender, MissingFontIsAWarningNotAFailure) {
  options_.font = "/nonexistent/font.ttf";
  const std::vector<PreviewPanel> estimates = {Scaled(1.02)};
  const PreviewResult result =
      RenderPreview(sphere_, truth_, estimates, AnalysePreviewErrors(truth_, estimates, {}), environment_, options_);
  ASSERT_EQ(result.warnings.size(), 1u);
  EXPECT_THAT(result.warnings[0], HasSubstr("/nonexistent/font.ttf"));
  EXPECT_EQ(result.image.width, ComputePreviewLayout(2, environment_.face_size, options_).width);
}

TEST(Preview, EnvironmentThumbnailBoxFiltersLargeCubesAndRepeatsSmallOnes) {
  const CubeMap constant = MakeConstant(8, glm::vec3(3.0f));
  for (int cross_face : {2, 4, 8, 16, 24}) {
    const Image thumbnail = EnvironmentThumbnail(constant, cross_face);
    ASSERT_EQ(thumbnail.width, 4 * cross_face);
    ASSERT_EQ(thumbnail.height, 3 * cross_face);
    // Constant radiance at exposure 1 / mean: 1 / (1 + 1) in every cell of the cross.
    const glm::vec3 centre = thumbnail.at(cross_face + cross_face / 2, cross_face + cross_face / 2);
    EXPECT_NEAR(centre.r, 0.5f, 1e-6f);
    EXPECT_EQ(thumbnail.at(0, 0), glm::vec3(0.0f));  // an unused cell
  }
}

}  // namespace
}  // namespace vs11::irradiance
