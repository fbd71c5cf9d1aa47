#include "vm/reference/sh_orders.h"

#include <cmath>
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "vm/reference/program_references.h"
#include "vm/reference/sphere_normals.h"

namespace vs11 {
namespace {

// Float registers against double polynomials: a few float roundings of values of order 1.
constexpr double kPackTolerance = 2e-6;

// The coefficients of a radiance concentrated in direction `d` (a delta of power `power` per channel).
Sh9Rgb DeltaLight(glm::dvec3 d, glm::dvec3 power) {
  const std::array<double, kSh9Coefficients> basis = ShBasis(glm::normalize(d));
  Sh9Rgb sh;
  for (int i = 0; i < kSh9Coefficients; ++i) sh.coefficients[i] = basis[i] * power;
  return sh;
}

double Band2Distance(const Sh9Rgb& a, const Sh9Rgb& b, int channel) {
  double sum = 0.0;
  for (int m = -2; m <= 2; ++m) {
    const double d = a.at(2, m)[channel] - b.at(2, m)[channel];
    sum += d * d;
  }
  return std::sqrt(sum);
}

TEST(ShOrder, NamesRoundTripAndAreOrderedBySlots) {
  int previous_slots = 0;
  for (ShOrder order : kAllShOrders) {
    EXPECT_EQ(kShOrderNames.Find(ShOrderName(order)), order);
    EXPECT_GT(Info(order).slots, previous_slots);
    previous_slots = Info(order).slots;
  }
  EXPECT_FALSE(kShOrderNames.Find("order3").has_value());
  EXPECT_EQ(kShOrderNames.List(), "order0, order1, zh3 or order2");
}

TEST(ShOrder, ReductionDropsWholeBands) {
  const Sh9Rgb sh = RandomCoefficients(7);
  const Sh9Rgb zero = ReduceToOrder(sh, ShOrder::kOrder0);
  const Sh9Rgb one = ReduceToOrder(sh, ShOrder::kOrder1);
  const Sh9Rgb two = ReduceToOrder(sh, ShOrder::kOrder2);
  for (int i = 0; i < kSh9Coefficients; ++i) {
    EXPECT_EQ(two.coefficients[i], sh.coefficients[i]);
    EXPECT_EQ(one.coefficients[i], i < 4 ? sh.coefficients[i] : glm::dvec3(0.0)) << i;
    EXPECT_EQ(zero.coefficients[i], i < 1 ? sh.coefficients[i] : glm::dvec3(0.0)) << i;
  }
}

// One light: band 2 is zonal around the light, and ZH3 finds that axis from band 1 and keeps it all.
TEST(ShOrder, Zh3IsExactForASingleLight) {
  const glm::dvec3 direction = glm::normalize(glm::dvec3(0.3, -0.5, 0.8));
  const Sh9Rgb sh = DeltaLight(direction, {2.0, 1.5, 0.5});
  const glm::dvec3 axis = Zh3Axis(sh);
  EXPECT_NEAR(glm::dot(axis, direction), 1.0, 1e-12);
  const Sh9Rgb zh3 = ReduceToOrder(sh, ShOrder::kZh3);
  for (int i = 0; i < kSh9Coefficients; ++i) {
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(zh3.coefficients[i][c], sh.coefficients[i][c], 1e-12) << i;
  }
}

// The zonal coefficient is band 2's projection: scaling it either way moves band 2 further away.
TEST(ShOrder, Zh3CoefficientIsTheBestZonalFitAroundItsAxis) {
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const Sh9Rgb sh = RandomCoefficients(seed);
    const Sh9Rgb zh3 = ReduceToOrder(sh, ShOrder::kZh3);
    for (double scale : {0.98, 1.02}) {
      Sh9Rgb scaled = zh3;
      for (int m = -2; m <= 2; ++m) scaled.at(2, m) *= scale;
      for (int c = 0; c < 3; ++c) {
        EXPECT_LE(Band2Distance(zh3, sh, c), Band2Distance(scaled, sh, c) + 1e-15) << seed;
      }
    }
  }
}

TEST(ShOrder, PackedRegistersGiveTheReducedIrradiance) {
  const std::vector<glm::dvec3> normals = SphereNormals(200);
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    const Sh9Rgb sh = RandomCoefficients(seed);
    for (ShOrder order : kAllShOrders) {
      const std::vector<NamedRegister> registers = PackShOrder(sh, order);
      ASSERT_EQ(static_cast<int>(registers.size()), Info(order).constant_registers);
      const Sh9Rgb reduced = ReduceToOrder(sh, order);
      for (const glm::dvec3& n : normals) {
        const glm::dvec3 expected = IrradianceEq7(reduced, n);
        const glm::dvec3 packed = EvaluateShOrder(registers, order, n);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(packed[c], expected[c], kPackTolerance) << ShOrderName(order);
      }
    }
  }
}

}  // namespace
}  // namespace vs11
