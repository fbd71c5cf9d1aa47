#include "irradiance/report/preview_errors.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>

#include "irradiance/sh/ground_truth.h"

namespace vs11::irradiance {
namespace {

constexpr std::array<double, 3> kNiceMantissas = {1.0, 2.0, 5.0};

}  // namespace

double RelativeError(glm::dvec3 estimate, glm::dvec3 truth, double floor) {
  double worst = 0.0;
  for (int c = 0; c < 3; ++c) {
    worst = std::max(worst, std::abs(estimate[c] - truth[c]) / std::max(std::abs(truth[c]), floor));
  }
  return worst;
}

double NicePreviewErrorScale(double max_error) {
  const double target = std::max(max_error, kMinPreviewErrorScale);
  double decade = std::pow(10.0, std::floor(std::log10(target)));
  for (int guard = 0; guard < 4; ++guard, decade *= 10.0) {
    for (double mantissa : kNiceMantissas) {
      // The 1e-9 keeps 0.02 (read as 0.0200000000004) from rounding up to 0.05.
      if (mantissa * decade >= target * (1.0 - 1e-9)) return mantissa * decade;
    }
  }
  return target;
}

PreviewErrors AnalysePreviewErrors(const PreviewPanel& truth, std::span<const PreviewPanel> estimates) {
  // The floor of CompareIrradiance.
  double truth_max = 0.0;
  for (const glm::dvec3& t : truth.irradiance) {
    truth_max = std::max({truth_max, std::abs(t.x), std::abs(t.y), std::abs(t.z)});
  }
  const double floor = kPreviewErrorFloor * truth_max;
  PreviewErrors errors;
  errors.relative.resize(estimates.size());
  double largest_error = 0.0;
  for (std::size_t p = 0; p < estimates.size(); ++p) {
    assert(estimates[p].irradiance.size() == truth.irradiance.size());
    errors.relative[p].resize(truth.irradiance.size());
    for (std::size_t k = 0; k < truth.irradiance.size(); ++k) {
      errors.relative[p][k] = RelativeError(estimates[p].irradiance[k], truth.irradiance[k], floor);
      largest_error = std::max(largest_error, errors.relative[p][k]);
    }
    errors.stats.push_back(CompareIrradiance(estimates[p].irradiance, truth.irradiance, kPreviewErrorFloor));
  }
  errors.scale = NicePreviewErrorScale(largest_error);
  return errors;
}

}  // namespace vs11::irradiance
