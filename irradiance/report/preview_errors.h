// The error analysis behind the preview's error row (render/preview.h draws it): the error of every
// sphere pixel of each estimate against the truth in the run's error metric, the caption under each
// error image, and the error scale the colour ramp of every error image shares.
#pragma once

#include <optional>
#include <span>
#include <string>

#include <glm/glm.hpp>

#include "irradiance/render/preview.h"
#include "irradiance/sh/ground_truth.h"

namespace vs11::irradiance {

// Relative errors: |estimate - truth| / max(truth, kPreviewErrorFloor x the brightest truth), the
// max over the three channels, the same definition as CompareIrradiance with its default floor.
inline constexpr double kPreviewErrorFloor = 0.01;
// The smallest error scale, 0.1 %: an almost perfect estimate would otherwise show its rounding
// noise at full scale.
inline constexpr double kMinPreviewErrorScale = 1e-3;

// The relative error of one sample: max over r, g, b of |e - t| / max(|t|, floor).
double RelativeError(glm::dvec3 estimate, glm::dvec3 truth, double floor);

// The smallest of 1, 2, 5 x 10^k (a fraction) not below `max_error` nor kMinPreviewErrorScale.
double NicePreviewErrorScale(double max_error);

// The figures of `metric` as a caption: "peak 9.38%, rms 14.4%" (kPeak), "rms 14.4%, peak 9.38%"
// (kRms), "max 62.4%, mean 10.9%" (kRelative), each rounded to 3 digits.
std::string ErrorCaption(const ErrorStats& stats, ErrorMetric metric);

// What the preview's error row is measured against. Empty `sphere_stats`: the captions are the
// statistics of the sphere's pixels, marked "(pixels)". Otherwise one ErrorStats per estimate, the
// same figures as irrmap's level table (every normal of the sphere, not only the visible half), and
// `sphere_scale` the per-channel SampleErrorScale of that table's truth, so that each pixel's error is
// a term of the table's figure.
struct PreviewErrorBasis {
  ErrorMetric metric = kDefaultErrorMetric;
  std::span<const ErrorStats> sphere_stats;
  std::optional<glm::dvec3> sphere_scale;
};

// The errors of each estimate panel against `truth` (each holding one irradiance per sphere pixel,
// sizes asserted), their captions, and the scale shared by every error image.
PreviewErrors AnalysePreviewErrors(const PreviewPanel& truth, std::span<const PreviewPanel> estimates,
                                   const PreviewErrorBasis& basis);

}  // namespace vs11::irradiance
