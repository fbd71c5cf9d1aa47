// Which rule a vs_1_1 product follows: IEEE's, as D3D9's reference rasterizer computes it, or the
// "0 * anything = 0" of DX8-era hardware (issue 20 §3; README "Float rules"). The engines and the
// translation apply it to every product an instruction computes (semantics::Product in
// vm/core/semantics.h); it is chosen when an engine is made or a program translated, never per product.
#pragma once

#include <cstdint>
#include "vm/core/name_table.h"

namespace vs11 {

enum class FloatRules : std::uint8_t {
  // IEEE single precision throughout: 0 * inf and 0 * NaN give NaN (the default).
  kD3d9,
  // Every product of mul, mad, dp3, dp4, the m*x* macros, dst and lit's power is
  // (b == 0 ? 0 : a) * (a == 0 ? 0 : b): a zero operand makes the product zero whatever the other is.
  // As NVIDIA's NV2x (the Xbox's NV2A) and ATI's R500 "legacy" mode compute it; the form is DXVK's
  // (d3d9.floatEmulation = Strict), and so is the sign of a zero result: the zero operand's own sign
  // when the other operand is not zero (0 * -5 = +0, -0 * 5 = -0), +0 when both are zero.
  kLegacy,
};

inline constexpr FloatRules kAllFloatRules[] = {FloatRules::kD3d9, FloatRules::kLegacy};

inline constexpr NameTable kFloatRulesNames("float rules", {
    Choice(FloatRules::kD3d9, "d3d9", "IEEE: 0 * inf = NaN"),
    Choice(FloatRules::kLegacy, "legacy", "0 * anything = 0, as DX8-era hardware and DXVK's strict mode")});

}  // namespace vs11
