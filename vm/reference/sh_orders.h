// The reduced SH orders: the irradiance of the nine coefficients approximated by cheaper vertex
// programs, each with its own packing. The references of those programs (program_references.h)
// read them; the irradiance library chooses among them (irradiance/sh/sh_order.h).
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

#include "vm/core/name_table.h"
#include "vm/reference/sh9.h"

namespace vs11 {

// One packed constant register with what it holds, as the irradiance library prints it
// (irradiance/sh/constants_output.h): name "cAr", contents "(c1 R11, c1 R1-1, c1 R10, c0 R00)".
struct NamedRegister {
  std::string name;      // "cAr"
  std::string contents;  // "(c1 R11, c1 R1-1, c1 R10, c0 R00)"
  glm::vec4 value{0.0f};
};

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

}  // namespace vs11
