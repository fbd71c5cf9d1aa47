// SH9 basis, irradiance by eqs. (6) and (7), and the constant-register packings. See sh9.h.
#include "vm/reference/sh9.h"

#include <cassert>
#include <cmath>

#include <fmt/format.h>

namespace vs11 {
namespace {

constexpr int kR = 0;
constexpr int kG = 1;
constexpr int kB = 2;
constexpr std::array<char, 3> kChannelLetters = {'R', 'G', 'B'};

// Coefficient (l, m) of one channel.
double Coef(const Sh9Rgb& sh, int l, int m, int channel) { return sh.at(l, m)[channel]; }

glm::vec4 ToFloat(double x, double y, double z, double w) {
  return glm::vec4(static_cast<float>(x), static_cast<float>(y), static_cast<float>(z),
                   static_cast<float>(w));
}

glm::dvec4 ToDouble(const glm::vec4& v) { return glm::dvec4(v); }

}  // namespace

std::array<double, kSh9Coefficients> ShBasis(glm::dvec3 d) {
  const double x = d.x;
  const double y = d.y;
  const double z = d.z;
  std::array<double, kSh9Coefficients> b{};
  b[ShIndex(0, 0)] = kShN0;
  b[ShIndex(1, -1)] = kShN1 * y;
  b[ShIndex(1, 0)] = kShN1 * z;
  b[ShIndex(1, 1)] = kShN1 * x;
  b[ShIndex(2, -2)] = kShN2 * x * y;
  b[ShIndex(2, -1)] = kShN2 * y * z;
  b[ShIndex(2, 0)] = kShN3 * (3.0 * z * z - 1.0);
  b[ShIndex(2, 1)] = kShN2 * x * z;
  b[ShIndex(2, 2)] = kShN4 * (x * x - y * y);
  return b;
}

glm::dvec3 IrradianceEq6(const Sh9Rgb& sh, glm::dvec3 n) {
  const std::array<double, kSh9Coefficients> basis = ShBasis(n);
  glm::dvec3 e(0.0);
  for (int l = 0; l < kSh9Bands; ++l) {
    for (int m = -l; m <= l; ++m) e += kShBandFactor[l] * basis[ShIndex(l, m)] * sh.at(l, m);
  }
  return e;
}

glm::dvec3 IrradianceEq7(const Sh9Rgb& sh, glm::dvec3 n) {
  const double x = n.x;
  const double y = n.y;
  const double z = n.z;
  glm::dvec3 e;
  for (int c = 0; c < 3; ++c) {
    e[c] = kShC0 * Coef(sh, 0, 0, c) - kShC3 * Coef(sh, 2, 0, c) +
           kShC1 * (Coef(sh, 1, -1, c) * y + Coef(sh, 1, 0, c) * z + Coef(sh, 1, 1, c) * x) +
           kShC2 * (Coef(sh, 2, -2, c) * x * y + Coef(sh, 2, -1, c) * y * z +
                    Coef(sh, 2, 1, c) * x * z) +
           3.0 * kShC3 * Coef(sh, 2, 0, c) * z * z + kShC4 * Coef(sh, 2, 2, c) * (x * x - y * y);
  }
  return e;
}

SevenConstants PackTable1(const Sh9Rgb& sh) {
  SevenConstants k;
  for (int c = 0; c < 3; ++c) {
    k.registers[SevenConstants::kA + c] =
        ToFloat(kShC1 * Coef(sh, 1, 1, c), kShC1 * Coef(sh, 1, -1, c), kShC1 * Coef(sh, 1, 0, c),
                kShC0 * Coef(sh, 0, 0, c) - kShC3 * Coef(sh, 2, 0, c));
    k.registers[SevenConstants::kB + c] =
        ToFloat(kShC2 * Coef(sh, 2, -2, c), kShC2 * Coef(sh, 2, -1, c),
                3.0 * kShC3 * Coef(sh, 2, 0, c), kShC2 * Coef(sh, 2, 1, c));
  }
  k.registers[SevenConstants::kC] = ToFloat(kShC4 * Coef(sh, 2, 2, kR), kShC4 * Coef(sh, 2, 2, kG),
                                            kShC4 * Coef(sh, 2, 2, kB), 0.0);
  return k;
}

SevenConstants PackUnitSphere10(const Sh9Rgb& sh) {
  SevenConstants k;
  glm::dvec3 yy_factor;
  for (int c = 0; c < 3; ++c) {
    const double l20 = Coef(sh, 2, 0, c);
    const double l22 = Coef(sh, 2, 2, c);
    k.registers[SevenConstants::kA + c] =
        ToFloat(kShC1 * Coef(sh, 1, 1, c), kShC1 * Coef(sh, 1, -1, c), kShC1 * Coef(sh, 1, 0, c),
                kShC0 * Coef(sh, 0, 0, c) + 2.0 * kShC3 * l20);
    k.registers[SevenConstants::kB + c] =
        ToFloat(kShC2 * Coef(sh, 2, -2, c), kShC2 * Coef(sh, 2, -1, c), kShC2 * Coef(sh, 2, 1, c),
                kShC4 * l22 - 3.0 * kShC3 * l20);
    yy_factor[c] = -kShC4 * l22 - 3.0 * kShC3 * l20;
  }
  k.registers[SevenConstants::kC] = ToFloat(yy_factor.x, yy_factor.y, yy_factor.z, 0.0);
  return k;
}

glm::dvec3 EvaluateTable1(const SevenConstants& k, glm::dvec3 n) {
  const glm::dvec4 linear(n.x, n.y, n.z, 1.0);
  const glm::dvec4 quadratic(n.x * n.y, n.y * n.z, n.z * n.z, n.z * n.x);
  const glm::dvec3 c = glm::dvec3(ToDouble(k.registers[SevenConstants::kC]));
  glm::dvec3 e;
  for (int ch = 0; ch < 3; ++ch) {
    e[ch] = glm::dot(linear, ToDouble(k.registers[SevenConstants::kA + ch])) +
            glm::dot(quadratic, ToDouble(k.registers[SevenConstants::kB + ch])) +
            c[ch] * (n.x * n.x - n.y * n.y);
  }
  return e;
}

glm::dvec3 EvaluateUnitSphere10(const SevenConstants& k, glm::dvec3 n) {
  const glm::dvec4 linear(n.x, n.y, n.z, 1.0);
  const glm::dvec4 quadratic(n.x * n.y, n.y * n.z, n.z * n.x, n.x * n.x);
  const glm::dvec3 c = glm::dvec3(ToDouble(k.registers[SevenConstants::kC]));
  glm::dvec3 e;
  for (int ch = 0; ch < 3; ++ch) {
    e[ch] = glm::dot(linear, ToDouble(k.registers[SevenConstants::kA + ch])) +
            glm::dot(quadratic, ToDouble(k.registers[SevenConstants::kB + ch])) +
            c[ch] * (n.y * n.y);
  }
  return e;
}

std::string Table1Contents(int index) {
  assert(index >= 0 && index < static_cast<int>(SevenConstants::kNames.size()));
  if (index == SevenConstants::kC) return "(c4 R22, c4 G22, c4 B22, unused)";
  if (index >= SevenConstants::kB) {
    const char c = kChannelLetters[index - SevenConstants::kB];
    return fmt::format("(c2 {0}2-2, c2 {0}2-1, 3 c3 {0}20, c2 {0}21)", c);
  }
  const char c = kChannelLetters[index - SevenConstants::kA];
  return fmt::format("(c1 {0}11, c1 {0}1-1, c1 {0}10, c0 {0}00 - c3 {0}20)", c);
}

}  // namespace vs11
