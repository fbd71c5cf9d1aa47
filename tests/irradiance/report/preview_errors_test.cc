#include "irradiance/report/preview_errors.h"

#include <algorithm>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace vs11::irradiance {
namespace {

// A truth of varied, positive irradiance (so the floor never applies).
PreviewPanel Truth() {
  PreviewPanel truth{"exact", {}};
  for (int i = 0; i < 50; ++i) truth.irradiance.push_back({1.0 + 0.1 * i, 2.0 + 0.05 * i, 0.5 + 0.2 * i});
  return truth;
}

// The truth scaled by `factor`: a relative error of |factor - 1| everywhere.
PreviewPanel Scaled(const PreviewPanel& truth, double factor) {
  PreviewPanel panel{"scaled", {}};
  for (const glm::dvec3& e : truth.irradiance) panel.irradiance.push_back(e * factor);
  return panel;
}

// Errors measured on the pixels alone, in `metric`.
PreviewErrorBasis PixelsOnly(ErrorMetric metric) {
  PreviewErrorBasis basis;
  basis.metric = metric;
  return basis;
}

TEST(PreviewErrors, ScaleIsTheNextNiceValueAboveTheLargestError) {
  const PreviewPanel truth = Truth();
  const std::vector<PreviewPanel> estimates = {Scaled(truth, 1.03), Scaled(truth, 0.99)};
  const PreviewErrors errors = AnalysePreviewErrors(truth, estimates, PixelsOnly(ErrorMetric::kRelative));
  EXPECT_DOUBLE_EQ(errors.scale, 0.05);
  ASSERT_EQ(errors.captions.size(), 2u);
  EXPECT_EQ(errors.captions[0], "max 3%, mean 3% (pixels)");
  EXPECT_EQ(errors.captions[1], "max 1%, mean 1% (pixels)");
  ASSERT_EQ(errors.per_pixel.size(), 2u);
  ASSERT_EQ(errors.per_pixel[1].size(), truth.irradiance.size());
  for (double e : errors.per_pixel[1]) EXPECT_NEAR(e, 0.01, 1e-9);
  const std::vector<PreviewPanel> exact = {Scaled(truth, 1.0)};
  EXPECT_DOUBLE_EQ(AnalysePreviewErrors(truth, exact, PixelsOnly(ErrorMetric::kRelative)).scale, kMinPreviewErrorScale);
}

// In the peak metric a pixel's error is |e - t| over the brightest truth of its channel: 3 % too
// bright everywhere is 3 % at the brightest pixel and less elsewhere; captions carry both figures.
TEST(PreviewErrors, PeakPixelErrorsAreFractionsOfThePeak) {
  const PreviewPanel truth = Truth();
  const std::vector<PreviewPanel> estimates = {Scaled(truth, 1.03)};
  const PreviewErrors errors = AnalysePreviewErrors(truth, estimates, PixelsOnly(ErrorMetric::kPeak));
  const glm::dvec3 peak = SampleErrorScale(truth.irradiance, ErrorMetric::kPeak);
  double largest = 0.0;
  for (std::size_t k = 0; k < truth.irradiance.size(); ++k) {
    const glm::dvec3 t = truth.irradiance[k];
    EXPECT_NEAR(errors.per_pixel[0][k], std::max({0.03 * t.x / peak.x, 0.03 * t.y / peak.y, 0.03 * t.z / peak.z}),
                1e-12);
    largest = std::max(largest, errors.per_pixel[0][k]);
  }
  EXPECT_NEAR(largest, 0.03, 1e-12);
  EXPECT_THAT(errors.captions[0], testing::StartsWith("peak 3%, rms "));
  EXPECT_EQ(errors.title, "error / peak E");
}

TEST(PreviewErrors, NiceScaleRoundsUpToOneTwoOrFiveTimesAPowerOfTen) {
  EXPECT_DOUBLE_EQ(NicePreviewErrorScale(0.011), 0.02);
  EXPECT_DOUBLE_EQ(NicePreviewErrorScale(0.02), 0.02);
  EXPECT_DOUBLE_EQ(NicePreviewErrorScale(0.3), 0.5);
  EXPECT_DOUBLE_EQ(NicePreviewErrorScale(0.6), 1.0);
  EXPECT_DOUBLE_EQ(NicePreviewErrorScale(0.0), kMinPreviewErrorScale);
}

TEST(PreviewErrors, RelativeErrorTakesTheWorstChannelAgainstTheFloor) {
  EXPECT_NEAR(RelativeError({1.1, 2.0, 0.0}, {1.0, 2.0, 0.0}, 0.5), 0.1, 1e-12);
  EXPECT_DOUBLE_EQ(RelativeError({0.0, 0.0, 0.2}, {0.0, 0.0, 0.1}, 0.5), 0.1 / 0.5);
}

}  // namespace
}  // namespace vs11::irradiance
