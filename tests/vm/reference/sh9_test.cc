#include "vm/reference/sh9.h"

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "vm/reference/sphere_normals.h"

namespace vs11 {
namespace {

// Ramamoorthi & Hanrahan 2001, eq. (13): their constants, printed to 6 decimals.
constexpr double kRhC1 = 0.429043;
constexpr double kRhC2 = 0.511664;
constexpr double kRhC3 = 0.743125;
constexpr double kRhC4 = 0.886227;
constexpr double kRhC5 = 0.247708;
// Their printed digits are not all correctly rounded: c2 (0.5116634 exact) and c3 (0.7431239
// exact) are off by 0.6e-6 and 1.1e-6. Every printed constant is within this of the exact value.
constexpr double kRhConstantError = 1.5e-6;
// So every term of their formula has at most this relative error (the error over the smallest
// constant, c5).
constexpr double kRhRelativeRounding = kRhConstantError / kRhC5;
// One float rounding per packed register entry (2^-24), with a factor 2 for the double evaluation.
constexpr double kFloatPackingRelative = 0x1p-23;
// Pure double arithmetic on a handful of terms.
constexpr double kDoubleTolerance = 1e-13;

glm::dvec3 RamamoorthiHanrahan(const Sh9Rgb& sh, glm::dvec3 n) {
  const double x = n.x, y = n.y, z = n.z;
  return kRhC1 * sh.at(2, 2) * (x * x - y * y) + kRhC3 * sh.at(2, 0) * z * z +
         kRhC4 * sh.at(0, 0) - kRhC5 * sh.at(2, 0) +
         2.0 * kRhC1 * (sh.at(2, -2) * x * y + sh.at(2, 1) * x * z + sh.at(2, -1) * y * z) +
         2.0 * kRhC2 * (sh.at(1, 1) * x + sh.at(1, -1) * y + sh.at(1, 0) * z);
}

// Sum of the magnitudes of the terms of eq. (7) for channel c: the scale of rounding errors.
double TermMagnitude(const Sh9Rgb& sh, glm::dvec3 n, int c) {
  const double x = std::abs(n.x), y = std::abs(n.y), z = std::abs(n.z);
  auto a = [&](int l, int m) { return std::abs(sh.at(l, m)[c]); };
  return kShC0 * a(0, 0) + kShC3 * a(2, 0) + kShC1 * (a(1, -1) * y + a(1, 0) * z + a(1, 1) * x) +
         kShC2 * (a(2, -2) * x * y + a(2, -1) * y * z + a(2, 1) * x * z) +
         3.0 * kShC3 * a(2, 0) * z * z + kShC4 * a(2, 2) * (x * x + y * y);
}

Sh9Rgb RandomSh(std::mt19937& rng) {
  std::uniform_real_distribution<double> coefficient(-2.0, 2.0);
  Sh9Rgb sh;
  for (glm::dvec3& c : sh.coefficients) c = {coefficient(rng), coefficient(rng), coefficient(rng)};
  sh.at(0, 0) += glm::dvec3(6.0);  // a plausible environment has a dominant L00
  return sh;
}

glm::dvec3 RandomUnit(std::mt19937& rng) {
  std::normal_distribution<double> gauss;
  glm::dvec3 v;
  do v = {gauss(rng), gauss(rng), gauss(rng)};
  while (glm::length(v) < 1e-3);
  return glm::normalize(v);
}

// Associated Legendre P_l^m(x) for l <= 2 without the Condon-Shortley sign, and the real basis of
// eq. (4): an independent (slow) route to eq. (5).
double Legendre(int l, int m, double x) {
  const double s = std::sqrt(1.0 - x * x);
  if (l == 0) return 1.0;
  if (l == 1) return m == 0 ? x : s;
  if (m == 0) return 0.5 * (3.0 * x * x - 1.0);
  return m == 1 ? 3.0 * x * s : 3.0 * (1.0 - x * x);
}
double Factorial(int n) { return n <= 1 ? 1.0 : n * Factorial(n - 1); }
double RealShSlow(int l, int m, double theta, double phi) {
  const int am = std::abs(m);
  const double k = std::sqrt((2 * l + 1) * Factorial(l - am) / (4.0 * std::numbers::pi * Factorial(l + am)));
  if (m > 0) return std::sqrt(2.0) * k * std::cos(m * phi) * Legendre(l, m, std::cos(theta));
  if (m < 0) return std::sqrt(2.0) * k * std::sin(-m * phi) * Legendre(l, -m, std::cos(theta));
  return k * Legendre(l, 0, std::cos(theta));
}

TEST(Sh9, IndexOrderIsLTimesLPlusOnePlusM) {
  EXPECT_EQ(ShIndex(0, 0), 0);
  EXPECT_EQ(ShIndex(1, -1), 1);
  EXPECT_EQ(ShIndex(1, 0), 2);
  EXPECT_EQ(ShIndex(1, 1), 3);
  EXPECT_EQ(ShIndex(2, -2), 4);
  EXPECT_EQ(ShIndex(2, 0), 6);
  EXPECT_EQ(ShIndex(2, 2), 8);
  Sh9Rgb sh;
  sh.at(2, 1) = glm::dvec3(1, 2, 3);
  EXPECT_EQ(sh.coefficients[7], glm::dvec3(1, 2, 3));
}

TEST(Sh9, ConstantsMatchRamamoorthiHanrahanToTheirPrintedDigits) {
  EXPECT_NEAR(kShC0, kRhC4, kRhConstantError);
  EXPECT_NEAR(kShC1, 2.0 * kRhC2, 2.0 * kRhConstantError);
  EXPECT_NEAR(kShC2, 2.0 * kRhC1, 2.0 * kRhConstantError);
  EXPECT_NEAR(kShC3, kRhC5, kRhConstantError);
  EXPECT_NEAR(3.0 * kShC3, kRhC3, kRhConstantError);
  EXPECT_NEAR(kShC4, kRhC1, kRhConstantError);
}

TEST(Sh9, BasisMatchesTheLegendreDefinitionOfEq4) {
  for (double theta : {0.1, 0.7, 1.3, 2.0, 2.9}) {
    for (double phi : {-2.5, -0.4, 0.0, 1.1, 3.0}) {
      const glm::dvec3 d(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                         std::cos(theta));
      const auto basis = ShBasis(d);
      for (int l = 0; l <= 2; ++l) {
        for (int m = -l; m <= l; ++m) {
          EXPECT_NEAR(basis[ShIndex(l, m)], RealShSlow(l, m, theta, phi), kDoubleTolerance)
              << "l=" << l << " m=" << m;
        }
      }
    }
  }
}

TEST(Sh9, BasisIsOrthonormalOverTheSphere) {
  // Equal-weight quadrature over a Fibonacci sphere of as many points as a 128 cube map has texels.
  constexpr int kPoints = 6 * 128 * 128;
  constexpr double kQuadratureTolerance = 2e-4;
  double gram[kSh9Coefficients][kSh9Coefficients] = {};
  const double weight = 4.0 * std::numbers::pi / kPoints;
  for (const glm::dvec3& n : SphereNormals(kPoints)) {
    const auto b = ShBasis(n);
    for (int i = 0; i < kSh9Coefficients; ++i) {
      for (int j = 0; j < kSh9Coefficients; ++j) gram[i][j] += b[i] * b[j] * weight;
    }
  }
  for (int i = 0; i < kSh9Coefficients; ++i) {
    for (int j = 0; j < kSh9Coefficients; ++j) {
      EXPECT_NEAR(gram[i][j], i == j ? 1.0 : 0.0, kQuadratureTolerance) << i << "," << j;
    }
  }
}

TEST(Sh9, AllFormsMatchRamamoorthiHanrahanClosedForm) {
  std::mt19937 rng(2001);
  for (int trial = 0; trial < 50; ++trial) {
    const Sh9Rgb sh = RandomSh(rng);
    const SevenConstants table1 = PackTable1(sh);
    const SevenConstants sphere10 = PackUnitSphere10(sh);
    for (int k = 0; k < 20; ++k) {
      const glm::dvec3 n = RandomUnit(rng);
      const glm::dvec3 reference = RamamoorthiHanrahan(sh, n);
      const glm::dvec3 eq6 = IrradianceEq6(sh, n);
      const glm::dvec3 eq7 = IrradianceEq7(sh, n);
      const glm::dvec3 t1 = EvaluateTable1(table1, n);
      const glm::dvec3 s10 = EvaluateUnitSphere10(sphere10, n);
      for (int c = 0; c < 3; ++c) {
        const double scale = TermMagnitude(sh, n, c);
        const double rh_tolerance = kRhRelativeRounding * scale;
        const double packed_tolerance = (kRhRelativeRounding + kFloatPackingRelative) * scale;
        EXPECT_NEAR(eq6[c], reference[c], rh_tolerance);
        EXPECT_NEAR(eq7[c], reference[c], rh_tolerance);
        EXPECT_NEAR(t1[c], reference[c], packed_tolerance);
        EXPECT_NEAR(s10[c], reference[c], packed_tolerance);
      }
    }
  }
}

TEST(Sh9, Eq6AndEq7AgreeOnUnitNormals) {
  std::mt19937 rng(6);
  for (int trial = 0; trial < 200; ++trial) {
    const Sh9Rgb sh = RandomSh(rng);
    const glm::dvec3 n = RandomUnit(rng);
    const glm::dvec3 e6 = IrradianceEq6(sh, n);
    const glm::dvec3 e7 = IrradianceEq7(sh, n);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(e6[c], e7[c], kDoubleTolerance * TermMagnitude(sh, n, c));
  }
}

TEST(Sh9, Eq6AsWrittenIsTheSamePolynomialAsEq7OffTheSphere) {
  // y20 is evaluated as 3 z^2 - 1, so eq. (6) equals eq. (7) for any vector, not just unit ones.
  std::mt19937 rng(7);
  for (int trial = 0; trial < 200; ++trial) {
    const Sh9Rgb sh = RandomSh(rng);
    const glm::dvec3 n = RandomUnit(rng) * (0.3 + 0.01 * trial);
    const glm::dvec3 e6 = IrradianceEq6(sh, n);
    const glm::dvec3 e7 = IrradianceEq7(sh, n);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(e6[c], e7[c], kDoubleTolerance * TermMagnitude(sh, n, c));
  }
}

TEST(Sh9, Table1MatchesEq7OffTheSphereToo) {
  std::mt19937 rng(71);
  for (int trial = 0; trial < 200; ++trial) {
    const Sh9Rgb sh = RandomSh(rng);
    const glm::dvec3 n = RandomUnit(rng) * (0.5 + 0.01 * trial);
    const glm::dvec3 t1 = EvaluateTable1(PackTable1(sh), n);
    const glm::dvec3 e7 = IrradianceEq7(sh, n);
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(t1[c], e7[c], kFloatPackingRelative * TermMagnitude(sh, n, c));
    }
  }
}

TEST(Sh9, UnitSphere10DiffersFromTable1OffTheSphereByThePredictedAmount) {
  std::mt19937 rng(10);
  for (int trial = 0; trial < 200; ++trial) {
    const Sh9Rgb sh = RandomSh(rng);
    const double length = 0.5 + 0.01 * trial;
    const glm::dvec3 n = RandomUnit(rng) * length;
    const glm::dvec3 t1 = EvaluateTable1(PackTable1(sh), n);
    const glm::dvec3 s10 = EvaluateUnitSphere10(PackUnitSphere10(sh), n);
    for (int c = 0; c < 3; ++c) {
      // Table1 - UnitSphere10 = 3 c3 L20 (x^2 + y^2 + z^2 - 1).
      const double predicted = 3.0 * kShC3 * sh.at(2, 0)[c] * (glm::dot(n, n) - 1.0);
      // Both packings are float-rounded; the terms reach |n|^2 times the unit-sphere magnitude.
      const double tolerance = 2.0 * kFloatPackingRelative * TermMagnitude(sh, n, c) *
                               std::max(1.0, glm::dot(n, n)) * 4.0;
      EXPECT_NEAR(t1[c] - s10[c], predicted, tolerance) << "|n|=" << length;
      if (std::abs(length - 1.0) > 0.1 && std::abs(sh.at(2, 0)[c]) > 0.1) {
        EXPECT_GT(std::abs(t1[c] - s10[c]), 10.0 * tolerance);  // really differs off the sphere
      }
    }
  }
}

TEST(Sh9, PackTable1LaysOutRegistersAsTable1) {
  Sh9Rgb sh;
  for (int i = 0; i < kSh9Coefficients; ++i) sh.coefficients[i] = glm::dvec3(i + 1, 10 * (i + 1), -(i + 1));
  const SevenConstants k = PackTable1(sh);
  EXPECT_STREQ(SevenConstants::kNames[0], "cAr");
  EXPECT_STREQ(SevenConstants::kNames[4], "cBg");
  EXPECT_STREQ(SevenConstants::kNames[6], "cC");
  for (int c = 0; c < 3; ++c) {
    auto l = [&](int band, int m) { return sh.at(band, m)[c]; };
    const glm::vec4 a = k.registers[SevenConstants::kA + c];
    const glm::vec4 b = k.registers[SevenConstants::kB + c];
    EXPECT_EQ(a.x, static_cast<float>(kShC1 * l(1, 1)));
    EXPECT_EQ(a.y, static_cast<float>(kShC1 * l(1, -1)));
    EXPECT_EQ(a.z, static_cast<float>(kShC1 * l(1, 0)));
    EXPECT_EQ(a.w, static_cast<float>(kShC0 * l(0, 0) - kShC3 * l(2, 0)));
    EXPECT_EQ(b.x, static_cast<float>(kShC2 * l(2, -2)));
    EXPECT_EQ(b.y, static_cast<float>(kShC2 * l(2, -1)));
    EXPECT_EQ(b.z, static_cast<float>(3.0 * kShC3 * l(2, 0)));
    EXPECT_EQ(b.w, static_cast<float>(kShC2 * l(2, 1)));
    EXPECT_EQ(k.registers[SevenConstants::kC][c], static_cast<float>(kShC4 * l(2, 2)));
  }
  EXPECT_EQ(k.registers[SevenConstants::kC].w, 0.0f);
}

}  // namespace
}  // namespace vs11
