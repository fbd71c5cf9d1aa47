// The error analysis behind the preview's error row (render/preview.h draws it): the relative error
// of every sphere pixel of each estimate against the truth, its statistics, and the error scale the
// colour ramp of every error image shares.
#pragma once

#include <span>

#include <glm/glm.hpp>

#include "irradiance/render/preview.h"

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

// The errors of each estimate panel against `truth` (each holding one irradiance per sphere pixel,
// sizes asserted), and the scale shared by every error image.
PreviewErrors AnalysePreviewErrors(const PreviewPanel& truth, std::span<const PreviewPanel> estimates);

}  // namespace vs11::irradiance
