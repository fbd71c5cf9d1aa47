// Choosing the mip level the coefficients come from by the error it may add ("model no more than a
// scene needs"), without the full-resolution coefficients or the ground truth: the error of level k
// against level 0 is estimated from the difference between level k and the next finer level k - 1.
//
// Why that works: a level's error against level 0 comes from treating the radiance as constant over
// each 2^k x 2^k block while the basis weight varies over it; for a smooth environment that error
// shrinks about fourfold per finer level (second order in the block size), so
//   error(k) = diff(k, k-1) + error(k-1) ~ diff(k, k-1) (1 + 1/4 + 1/16 + ...) = 4/3 diff(k, k-1).
// Sharp features (a light covering a few texels) break the fourfold rule at the coarse end; the
// factor below is fitted to what the built-in environments showed (irrmap stability measures it).
#pragma once

#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "irradiance/sh/ground_truth.h"
#include "irradiance/sh/sh9.h"

namespace vs11::irradiance {

// irrmap's default --max-error: the coarsest level whose estimated error stays under 0.5 %.
inline constexpr double kDefaultMaxLevelError = 0.005;
// estimate(k) = kLevelErrorEstimateFactor x diff(k, k-1): 4/3 from the geometric series above plus
// 5 %. Measured (irrmap stability, and 15 environments x face sizes 128, 256, 512 x E from 0.1 % to
// 2 %): the true error is 0.75 to 1.53 times diff(k, k-1) where it lies between 0.01 % and 5 %, and
// with this factor the pick met E in 194 of 195 cases (the miss: 0.503 % for E = 0.5 %) while the
// next coarser level exceeded E in 180; a factor of 2 met all 195 but was needlessly fine in 56.
inline constexpr double kLevelErrorEstimateFactor = 1.4;
// Normals (SphereNormals) at which levels are compared: the irradiance is a quadratic polynomial,
// so a few hundred directions find its largest difference to a few per cent.
inline constexpr int kLevelErrorNormals = 512;
// Relative errors use CompareIrradiance's floor of 1 % of the largest reference value, so black
// directions (behind a single light) do not dominate.
inline constexpr double kLevelErrorFloorFraction = 0.01;

// The difference, as `metric`'s figure (ErrorFigure of CompareIrradiance, floor
// kLevelErrorFloorFraction), of the irradiance (eq. 7, per channel) of `estimate` against that of
// `reference` at `normals`.
double IrradianceDifference(const Sh9Rgb& estimate, const Sh9Rgb& reference, std::span<const glm::dvec3> normals,
                            ErrorMetric metric);

// For levels[0] (finest) to levels.back() (coarsest), the estimated error (`metric`'s figure) of
// each level's irradiance against level 0's: 0 for level 0, `factor` x
// IrradianceDifference(levels[k], levels[k - 1]) for the others.
std::vector<double> EstimateLevelErrors(std::span<const Sh9Rgb> levels, std::span<const glm::dvec3> normals,
                                        ErrorMetric metric, double factor = kLevelErrorEstimateFactor);

// The coarsest level k such that every level 0..k has an estimated error <= max_error (so a noisy
// coarse level that happens to look good is never chosen across a bad one); 0 when none does.
// `estimated` as from EstimateLevelErrors, non-empty (asserted).
int CoarsestLevelWithin(std::span<const double> estimated, double max_error);

}  // namespace vs11::irradiance
