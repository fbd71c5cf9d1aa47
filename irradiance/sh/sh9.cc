// SH9 basis, irradiance by eqs. (6) and (7), and the constant-register packings. See sh9.h.
#include "irradiance/sh/sh9.h"

#include <algorithm>
#include <cmath>

namespace vs11::irradiance {
namespace {

constexpr int kR = 0;
constexpr int kG = 1;
constexpr int kB = 2;

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

double BandNorm(const Sh9Rgb& sh, int band, int channel) {
  assert(band >= 0 && band < kSh9Bands && channel >= 0 && channel < 3);
  double sum = 0.0;
  for (int m = -band; m <= band; ++m) {
    const double v = Coef(sh, band, m, channel);
    sum += v * v;
  }
  return std::sqrt(sum);
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

std::array<double, kSh9Bands> ShWindowFactors(ShWindow window, double width) {
  assert(window != ShWindow::kDering && window != ShWindow::kNonNegative);
  std::array<double, kSh9Bands> factors = {1.0, 1.0, 1.0};
  if (window == ShWindow::kNone) return factors;
  assert(width > 0.0);
  for (int l = 1; l < kSh9Bands; ++l) {
    const double t = l / width;
    if (t >= 1.0) {
      factors[l] = 0.0;
    } else if (window == ShWindow::kHanning) {
      factors[l] = 0.5 * (1.0 + std::cos(std::numbers::pi * t));
    } else {
      factors[l] = std::sin(std::numbers::pi * t) / (std::numbers::pi * t);
    }
  }
  return factors;
}

std::array<double, kSh9Bands> LaplacianWindowFactors(double lambda) {
  assert(lambda >= 0.0);
  std::array<double, kSh9Bands> factors{};
  for (int l = 0; l < kSh9Bands; ++l) factors[l] = 1.0 / (1.0 + lambda * l * l * (l + 1) * (l + 1));
  return factors;
}

Sh9Rgb ApplyShWindow(const Sh9Rgb& sh, const std::array<double, kSh9Bands>& factors) {
  Sh9Rgb windowed = sh;
  for (int l = 0; l < kSh9Bands; ++l) {
    for (int m = -l; m <= l; ++m) windowed.at(l, m) *= factors[l];
  }
  return windowed;
}

namespace {

// Lambda search range and precision of DeringLambda.
constexpr double kDeringFirstLambda = 1e-3;
constexpr double kDeringMaxLambda = 1e6;
constexpr double kDeringRelativePrecision = 1e-4;
// Irradiance this far below zero, relative to the largest |E|, counts as zero: rounding leaves
// such crumbs where the true band-limited irradiance is exactly 0.
constexpr double kDeringZeroTolerance = 1e-9;

double MinimumIrradiance(const Sh9Rgb& sh, std::span<const glm::dvec3> normals, double& largest) {
  double lowest = 0.0;
  largest = 0.0;
  for (const glm::dvec3& n : normals) {
    const glm::dvec3 e = IrradianceEq7(sh, n);
    for (int c = 0; c < 3; ++c) {
      lowest = std::min(lowest, e[c]);
      largest = std::max(largest, std::abs(e[c]));
    }
  }
  return lowest;
}

bool NonNegative(const Sh9Rgb& sh, std::span<const glm::dvec3> normals, double lambda) {
  double largest = 0.0;
  const double lowest = MinimumIrradiance(ApplyShWindow(sh, LaplacianWindowFactors(lambda)), normals, largest);
  return lowest >= -kDeringZeroTolerance * largest;
}

}  // namespace

double DeringLambda(const Sh9Rgb& sh, std::span<const glm::dvec3> normals) {
  if (NonNegative(sh, normals, 0.0)) return 0.0;
  double high = kDeringFirstLambda;
  while (!NonNegative(sh, normals, high)) {
    if (high >= kDeringMaxLambda) return kDeringMaxLambda;
    high *= 2.0;
  }
  double low = high == kDeringFirstLambda ? 0.0 : 0.5 * high;
  while (high - low > kDeringRelativePrecision * high) {
    const double middle = 0.5 * (low + high);
    (NonNegative(sh, normals, middle) ? high : low) = middle;
  }
  return high;
}

}  // namespace vs11::irradiance
