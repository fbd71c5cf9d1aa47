#include "irradiance/report/preview_errors.h"

#include <vector>

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

TEST(PreviewErrors, ScaleIsTheNextNiceValueAboveTheLargestError) {
  const PreviewPanel truth = Truth();
  const std::vector<PreviewPanel> estimates = {Scaled(truth, 1.03), Scaled(truth, 0.99)};
  const PreviewErrors errors = AnalysePreviewErrors(truth, estimates, {ErrorMetric::kRelative});
  EXPECT_DOUBLE_EQ(errors.scale, 0.05);
  ASSERT_EQ(errors.captions.size(), 2u);
  EXPECT_EQ(errors.captions[0], "max 3%, mean 3% (pixels)");
  EXPECT_EQ(errors.captions[1], "max 1%, mean 1% (pixels)");
  ASSERT_EQ(errors.per_pixel.size(), 2u);
  ASSERT_EQ(errors.per_pixel[1].size(), truth.irradiance.size());
  for (double e : errors.per_pixel[1]) EXPECT_NEAR(e, 0.01, 1e-9);
  const std::vector<PreviewPanel> exact = {Scaled(truth, 1.0)};
  EXPECT_DOUBLE_EQ(AnalysePreviewErrors(truth, exact, {ErrorMetric::kRelative}).scale, kMinPreviewErrorScale);
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
