// The SH order as part of the cost model ("model no more than a scene needs"): the irradiance of
// the nine coefficients approximated by cheaper vertex programs, each with its own packing, and the
// choice of (program, mip level) by an error target.
//
//   program            slots  constants  irradiance per channel
//   sh_order0.vsh          1          1  c0 L00                                   (band 0)
//   sh_order1.vsh          3          3  c0 L00 + c1 L1.n                         (bands 0, 1)
//   sh_zh3.vsh             6          5  order 1 + A2 z n3 (3 (a.n)^2 - 1)        (ZH3)
//   sh9_irradiance.vsh    11          7  the paper's eq. (7)                      (bands 0..2)
//
// Each reduced order is itself a set of nine coefficients (ReduceToOrder), so eq. (7) and every
// error measure apply to it unchanged. Dropping whole bands is the least-squares best fit of the
// nine-term irradiance by the lower bands (the bands are orthogonal over the sphere). ZH3 keeps of
// band 2 only its projection on the zonal harmonic around the axis a of the linear band's
// luminance (Roughton et al., "ZH3: Quadratic Zonal Harmonics", i3D 2024), one coefficient z per
// channel; the axis is shared so that the three channels need one dp3.
#pragma once

#include <array>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "irradiance/sh/constants_output.h"
#include "irradiance/sh/ground_truth.h"
#include "irradiance/sh/sh9.h"
#include "vm/core/name_table.h"

namespace vs11::irradiance {

enum class ShOrder { kOrder0, kOrder1, kZh3, kOrder2 };

// The programs, cheapest first (the order of the table above).
inline constexpr std::array<ShOrder, 4> kAllShOrders = {ShOrder::kOrder0, ShOrder::kOrder1, ShOrder::kZh3,
                                                        ShOrder::kOrder2};

// The names of --order and coeffs.json.
inline constexpr NameTable kShOrderNames("order", {
    Choice(ShOrder::kOrder0, "order0", "1 slot, constant"), Choice(ShOrder::kOrder1, "order1", "3 slots, bands 0-1"),
    Choice(ShOrder::kZh3, "zh3", "6 slots, bands 0-1 plus one zonal band-2 term"),
    Choice(ShOrder::kOrder2, "order2", "the paper's 11 slots")});
inline std::string_view ShOrderName(ShOrder order) { return kShOrderNames.Name(order); }

struct ShOrderInfo {
  ShOrder order;
  std::string_view program_file;  // in programs/
  int slots = 0;                  // instruction slots per vertex (ComputeStats; a test checks them)
  int constant_registers = 0;     // c0.. that the program reads
  double sh_order = 0;            // highest band used: 0, 1, 1.5 (ZH3: one band-2 term), 2
};
const ShOrderInfo& Info(ShOrder order);

// The ZH3 axis: the unit direction (x, y, z) of the luminance (Rec. 709 weights) of the linear
// band, (L11, L1-1, L10); +z when that is zero (the zonal term is then along an arbitrary axis,
// and still the best one-coefficient fit around it).
glm::dvec3 Zh3Axis(const Sh9Rgb& sh);

// The nine coefficients whose irradiance (eq. 6/7) is what the order's program computes: bands
// above the order zeroed; for ZH3, band 2 replaced by its zonal part around Zh3Axis(sh).
Sh9Rgb ReduceToOrder(const Sh9Rgb& sh, ShOrder order);

// The registers the order's program reads, from c0 on (Info(order).constant_registers of them),
// each entry computed in double and rounded to float once. kOrder2 gives the seven of PackTable1.
std::vector<NamedRegister> PackShOrder(const Sh9Rgb& sh, ShOrder order);
// The program's polynomial evaluated in double from the packed registers (a reference for tests).
glm::dvec3 EvaluateShOrder(std::span<const NamedRegister> registers, ShOrder order, glm::dvec3 n);

// ---- The choice of (program, level) ------------------------------------------------------------------

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
