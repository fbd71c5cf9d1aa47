// The SH order as part of the cost model ("model no more than a scene needs"): the choice of
// (program, mip level) among the reduced orders (vm/reference/sh_orders.h) by an error target.
#pragma once

#include <span>

#include <glm/glm.hpp>

#include "irradiance/sh/ground_truth.h"
#include "vm/reference/sh_orders.h"

namespace vs11::irradiance {

// estimate(order, k) = estimated level error (EstimateLevelErrors) + kOrderErrorEstimateFactor x
// IrradianceDifference(ReduceToOrder(level k), level k). The second term is computed, not
// extrapolated: it is the order's exact error against order 2 at that level, measured on
// kLevelErrorNormals normals. The factor covers what those normals miss between them and how the
// two errors add up. Fitted on the stability set (irrmap stability, "Order choice").
inline constexpr double kOrderErrorEstimateFactor = 1.1;

struct ProgramLevelEstimate {
  ShOrder order = ShOrder::kOrder2;
  int level = 0;
  double order_difference = 0.0;  // IrradianceDifference(reduced, level k's order 2)
  double estimated = 0.0;         // against order 2 at level 0, as above
};

// Every (order, level) pair, orders in kAllShOrders order, levels 0 first within each.
// `levels[k]` are level k's nine coefficients, `level_estimates` EstimateLevelErrors of them in the
// same `metric`, which the order differences are measured in too.
std::vector<ProgramLevelEstimate> EstimateProgramLevelErrors(std::span<const Sh9Rgb> levels,
                                                             std::span<const double> level_estimates,
                                                             std::span<const glm::dvec3> normals, ErrorMetric metric,
                                                             double factor = kOrderErrorEstimateFactor);

struct ProgramChoice {
  ShOrder order = ShOrder::kOrder2;
  int level = 0;
  double estimated = 0.0;
};
// The cheapest pair within max_error: fewest slots first, then the coarsest level (the cheapest
// update) among those whose estimate is <= max_error and whose finer levels all have level
// estimates <= max_error (as CoarsestLevelWithin). Order 2 at level 0 (estimate 0) always
// qualifies. `allowed` restricts the orders (empty: all). Pairs as from EstimateProgramLevelErrors.
ProgramChoice ChooseProgramAndLevel(std::span<const ProgramLevelEstimate> pairs,
                                    std::span<const double> level_estimates, double max_error,
                                    std::span<const ShOrder> allowed = {});

}  // namespace vs11::irradiance
