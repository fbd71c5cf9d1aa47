#include "irradiance/sh/sh9.h"

#include <gtest/gtest.h>

namespace vs11::irradiance {
namespace {

TEST(Sh9, BandNormIsTheRootSumOfSquaresOfOneBand) {
  Sh9Rgb sh;
  sh.at(0, 0) = glm::dvec3(-2.0, 0.0, 1.0);
  sh.at(1, -1) = glm::dvec3(3.0, 0.0, 0.0);
  sh.at(1, 1) = glm::dvec3(4.0, 0.0, 0.0);
  sh.at(2, 2) = glm::dvec3(0.0, 0.0, 5.0);
  EXPECT_DOUBLE_EQ(BandNorm(sh, 0, 0), 2.0);
  EXPECT_DOUBLE_EQ(BandNorm(sh, 1, 0), 5.0);
  EXPECT_DOUBLE_EQ(BandNorm(sh, 1, 1), 0.0);
  EXPECT_DOUBLE_EQ(BandNorm(sh, 2, 2), 5.0);
}

}  // namespace
}  // namespace vs11::irradiance
