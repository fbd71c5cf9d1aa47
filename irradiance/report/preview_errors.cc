#include "irradiance/report/preview_errors.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>

#include <fmt/format.h>

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

std::string ErrorCaption(const ErrorStats& stats, ErrorMetric metric) {
  auto percent = [](double fraction) {
    const double value = 100.0 * fraction;
    return value >= 100.0 ? fmt::format("{:.0f}%", value) : fmt::format("{:.3g}%", value);
  };
  switch (metric) {
    case ErrorMetric::kRelative:
      return fmt::format("max {}, mean {}", percent(stats.max_relative), percent(stats.mean_relative));
    case ErrorMetric::kPeak: return fmt::format("peak {}, rms {}", percent(stats.max_peak), percent(stats.max_rms));
    case ErrorMetric::kRms: return fmt::format("rms {}, peak {}", percent(stats.max_rms), percent(stats.max_peak));
  }
  return {};
}

PreviewErrors AnalysePreviewErrors(const PreviewPanel& truth, std::span<const PreviewPanel> estimates,
                                   const PreviewErrorBasis& basis) {
  assert(basis.sphere_stats.empty() || basis.sphere_stats.size() == estimates.size());
  const glm::dvec3 scale = basis.sphere_scale ? *basis.sphere_scale
                                               : SampleErrorScale(truth.irradiance, basis.metric, kPreviewErrorFloor);
  PreviewErrors errors;
  errors.per_pixel.resize(estimates.size());
  double largest_error = 0.0;
  for (std::size_t p = 0; p < estimates.size(); ++p) {
    assert(estimates[p].irradiance.size() == truth.irradiance.size());
    errors.per_pixel[p].resize(truth.irradiance.size());
    for (std::size_t k = 0; k < truth.irradiance.size(); ++k) {
      errors.per_pixel[p][k] = SampleError(estimates[p].irradiance[k], truth.irradiance[k], scale, basis.metric);
      largest_error = std::max(largest_error, errors.per_pixel[p][k]);
    }
    if (basis.sphere_stats.empty()) {
      const ErrorStats pixels = CompareIrradiance(estimates[p].irradiance, truth.irradiance, kPreviewErrorFloor);
      errors.captions.push_back(ErrorCaption(pixels, basis.metric) + " (pixels)");
    } else {
      errors.captions.push_back(ErrorCaption(basis.sphere_stats[p], basis.metric));
    }
  }
  switch (basis.metric) {
    case ErrorMetric::kRelative: errors.title = "relative error"; break;
    case ErrorMetric::kPeak: errors.title = "error / peak E"; break;
    case ErrorMetric::kRms: errors.title = "error / mean E"; break;
  }
  errors.scale = NicePreviewErrorScale(largest_error);
  return errors;
}

}  // namespace vs11::irradiance
