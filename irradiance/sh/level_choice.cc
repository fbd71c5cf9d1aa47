// Level choice by estimated error. See level_choice.h.
#include "irradiance/sh/level_choice.h"

#include <cassert>
#include <cstddef>

#include "irradiance/sh/ground_truth.h"

namespace vs11::irradiance {

double IrradianceDifference(const Sh9Rgb& estimate, const Sh9Rgb& reference, std::span<const glm::dvec3> normals,
                            ErrorMetric metric) {
  std::vector<glm::dvec3> estimated(normals.size());
  std::vector<glm::dvec3> referenced(normals.size());
  for (std::size_t i = 0; i < normals.size(); ++i) {
    estimated[i] = IrradianceEq7(estimate, normals[i]);
    referenced[i] = IrradianceEq7(reference, normals[i]);
  }
  return ErrorFigure(CompareIrradiance(estimated, referenced, kLevelErrorFloorFraction), metric);
}

std::vector<double> EstimateLevelErrors(std::span<const Sh9Rgb> levels, std::span<const glm::dvec3> normals,
                                        ErrorMetric metric, double factor) {
  std::vector<double> estimated(levels.size(), 0.0);
  for (std::size_t k = 1; k < levels.size(); ++k) {
    estimated[k] = factor * IrradianceDifference(levels[k], levels[k - 1], normals, metric);
  }
  return estimated;
}

int CoarsestLevelWithin(std::span<const double> estimated, double max_error) {
  assert(!estimated.empty());
  int level = 0;
  while (level + 1 < static_cast<int>(estimated.size()) && estimated[level + 1] <= max_error) ++level;
  return level;
}

}  // namespace vs11::irradiance
