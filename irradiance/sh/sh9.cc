// Band norms and windows of the nine coefficients. See sh9.h.
#include "irradiance/sh/sh9.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace vs11::irradiance {

double BandNorm(const Sh9Rgb& sh, int band, int channel) {
  assert(band >= 0 && band < kSh9Bands && channel >= 0 && channel < 3);
  double sum = 0.0;
  for (int m = -band; m <= band; ++m) {
    const double v = sh.at(band, m)[channel];
    sum += v * v;
  }
  return std::sqrt(sum);
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
