// The seven constant registers of the paper's Table 1 (SevenConstants, irradiance/sh/sh9.h) written out
// for other programs: as vs_1_1 `def` lines, as a C++ header and as JSON. Every float is printed in
// its shortest round-trip form (vs11::FormatFloat), so reading any of the three back gives the same
// bits.
//
//   register  x          y           z           w
//   cAr       c1 R11     c1 R1-1     c1 R10      c0 R00 - c3 R20     (cAg, cAb alike for G, B)
//   cBr       c2 R2-2    c2 R2-1     3 c3 R20    c2 R21              (cBg, cBb alike)
//   cC        c4 R22     c4 G22      c4 B22      0 (unused)
#pragma once

#include <span>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "irradiance/sh/sh9.h"
#include "vm/reference/sh_orders.h"

namespace vs11::irradiance {

// One line per register,
//   def c<base + i>, x, y, z, w  ; cAr = (c1 R11, c1 R1-1, c1 R10, c0 R00 - c3 R20)
// in SevenConstants order, preceded by `header_comment` (each of its lines prefixed with "; ") when
// it is not empty. The result is accepted both by the assembler (inside a program, after the
// version line) and by vs11::ParseConstantsText (`vs11 run --consts`). base_register >= 0.
std::string ConstantsDefText(const SevenConstants& constants, int base_register = 0,
                             std::string_view header_comment = {});

// The same layout for any list of registers (the reduced orders' programs, irradiance/sh/sh_order.h):
//   def c<base + i>, x, y, z, w  ; <name> = <contents>
// ConstantsDefText is this with the seven Table 1 registers (NamedRegister: vm/reference/sh_orders.h).
std::string RegisterDefText(std::span<const NamedRegister> registers, int base_register = 0,
                            std::string_view header_comment = {});

// A self-contained C++ header:
//   inline constexpr float kCAr[4] = {0.25f, -1.0f, 3e-05f, 1.5f};  // c1 R11, ...
// one array per register (kCAr kCAg kCAb kCBr kCBg kCBb kCC), inside `namespace_name` when it is
// not empty. Non-finite values are spelled with std::numeric_limits (and <limits> is included).
std::string ConstantsCppHeader(const SevenConstants& constants, std::string_view namespace_name = {},
                               std::string_view header_comment = {});

// {"cAr": [x, y, z, w], ..., "cC": [...]}: the seven registers by name in Table 1 order, values as JSON numbers
// (non-finite values become null, which JSON cannot otherwise hold).
nlohmann::ordered_json ConstantsJson(const SevenConstants& constants);

}  // namespace vs11::irradiance
