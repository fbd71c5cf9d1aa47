// The (program, level) choice among the reduced orders. See sh_order.h.
#include "irradiance/sh/sh_order.h"

#include <algorithm>
#include <cassert>

#include "irradiance/sh/level_choice.h"

namespace vs11::irradiance {

std::vector<ProgramLevelEstimate> EstimateProgramLevelErrors(std::span<const Sh9Rgb> levels,
                                                             std::span<const double> level_estimates,
                                                             std::span<const glm::dvec3> normals, ErrorMetric metric,
                                                             double factor) {
  assert(levels.size() == level_estimates.size());
  std::vector<ProgramLevelEstimate> pairs;
  for (ShOrder order : kAllShOrders) {
    for (std::size_t k = 0; k < levels.size(); ++k) {
      ProgramLevelEstimate pair;
      pair.order = order;
      pair.level = static_cast<int>(k);
      if (order != ShOrder::kOrder2) {
        pair.order_difference = IrradianceDifference(ReduceToOrder(levels[k], order), levels[k], normals, metric);
      }
      pair.estimated = level_estimates[k] + factor * pair.order_difference;
      pairs.push_back(pair);
    }
  }
  return pairs;
}

ProgramChoice ChooseProgramAndLevel(std::span<const ProgramLevelEstimate> pairs,
                                    std::span<const double> level_estimates, double max_error,
                                    std::span<const ShOrder> allowed) {
  auto is_allowed = [&](ShOrder order) {
    return allowed.empty() || std::find(allowed.begin(), allowed.end(), order) != allowed.end();
  };
  // Levels 0..finest_bad - 1 all have level estimates within max_error.
  std::size_t finest_bad = 1;
  while (finest_bad < level_estimates.size() && level_estimates[finest_bad] <= max_error) ++finest_bad;
  for (ShOrder order : kAllShOrders) {
    if (!is_allowed(order)) continue;
    std::optional<ProgramChoice> best;
    for (const ProgramLevelEstimate& pair : pairs) {
      if (pair.order != order || pair.level >= static_cast<int>(finest_bad) || pair.estimated > max_error) continue;
      if (!best || pair.level > best->level) best = ProgramChoice{order, pair.level, pair.estimated};
    }
    if (best) return *best;
  }
  // Nothing allowed meets max_error: the most accurate allowed pair, level 0 of the last order.
  for (auto it = kAllShOrders.rbegin(); it != kAllShOrders.rend(); ++it) {
    if (!is_allowed(*it)) continue;
    for (const ProgramLevelEstimate& pair : pairs) {
      if (pair.order == *it && pair.level == 0) return {*it, 0, pair.estimated};
    }
  }
  return {};
}

}  // namespace vs11::irradiance
