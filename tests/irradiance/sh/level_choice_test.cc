// The level choice: the estimate of a level's error from its finer neighbour, and the coarsest level
// whose every finer level passes too.
#include "irradiance/sh/level_choice.h"

#include <vector>

#include <gtest/gtest.h>

#include "irradiance/sh/ground_truth.h"

namespace vs11::irradiance {
namespace {

Sh9Rgb Constant(double l00) {
  Sh9Rgb sh;
  sh.at(0, 0) = glm::dvec3(l00);
  return sh;
}

TEST(LevelChoice, IdenticalLevelsDifferByNothing) {
  const std::vector<glm::dvec3> normals = SphereNormals(kLevelErrorNormals);
  const std::vector<Sh9Rgb> levels(4, Constant(2.0));
  for (ErrorMetric metric : kAllErrorMetrics) {
    EXPECT_EQ(IrradianceDifference(Constant(1.0), Constant(1.0), normals, metric), 0.0);
    EXPECT_EQ(EstimateLevelErrors(levels, normals, metric), std::vector<double>(4, 0.0));
  }
}

TEST(LevelChoice, EstimateIsTheFactorTimesTheDifferenceFromTheFinerLevel) {
  const std::vector<glm::dvec3> normals = SphereNormals(64);
  // A constant environment: the irradiance is pi * Y00 * L00 everywhere, so 1 % more L00 is 1 % more
  // irradiance in every direction: relative, peak and RMS errors alike.
  const std::vector<Sh9Rgb> levels = {Constant(1.0), Constant(1.01), Constant(1.0302)};
  for (ErrorMetric metric : kAllErrorMetrics) {
    const std::vector<double> estimated = EstimateLevelErrors(levels, normals, metric, 2.0);
    ASSERT_EQ(estimated.size(), 3u);
    EXPECT_EQ(estimated[0], 0.0);
    EXPECT_NEAR(estimated[1], 2.0 * 0.01, 1e-12) << ErrorMetricName(metric);
    EXPECT_NEAR(estimated[2], 2.0 * 0.02, 1e-12) << ErrorMetricName(metric);
  }
}

TEST(LevelChoice, CoarsestLevelStopsAtTheFirstLevelOverTheLimit) {
  EXPECT_EQ(CoarsestLevelWithin(std::vector<double>{0.0, 0.001, 0.004, 0.02}, 0.005), 2);
  // A coarse level that happens to look good after a bad one is not chosen.
  EXPECT_EQ(CoarsestLevelWithin(std::vector<double>{0.0, 0.001, 0.02, 0.001}, 0.005), 1);
  EXPECT_EQ(CoarsestLevelWithin(std::vector<double>{0.0, 0.5}, 0.005), 0);
  EXPECT_EQ(CoarsestLevelWithin(std::vector<double>{0.0}, 0.005), 0);
  EXPECT_EQ(CoarsestLevelWithin(std::vector<double>{0.0, 0.005}, 0.005), 1);  // the limit itself passes
}

}  // namespace
}  // namespace vs11::irradiance
