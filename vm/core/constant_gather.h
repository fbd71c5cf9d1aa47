// Relative constant reads, c[a0.x + n], as the batch and jit engines gather them from their constant
// table (vm/engines/batch_plan.h: rows of four floats, row 0 all zeros, register c# at row
// first_row + #), written once over an int32 lane type I: std::int32_t (one vertex), a Highway
// vector, or a traced graph value, each with +, >, IfThenElseZero and ShiftLeft found by ordinary or
// argument-dependent lookup. Registers outside the bank [0, count) read row 0, as the reference
// engine's constant bank reads 0 for them (and a0 saturates at +-2^20, vm/core/operands.h, so the
// sum cannot overflow). Like semantics.h, the batch kernels include this under their target pragma.
#pragma once

#include <cstdint>

#include "vm/core/semantics.h"

namespace vs11::semantics {

inline std::int32_t IfThenElseZero(bool condition, std::int32_t value) { return condition ? value : 0; }

// The offset in floats of component 0 of the row that c[index] reads, `count` holding the bank's
// size per lane; `literal(n)` makes an I holding n in every lane. This is the IR's kRelativeRow
// (vm/ir/graph.h) as the jit lowers it.
template <class I, class Literal>
I ConstantRowOffset(I index, I count, std::int32_t first_row, Literal literal) {
  const I row_if_below_count = IfThenElseZero(count > index, index + literal(first_row));
  return ShiftLeft<2>(IfThenElseZero(index > literal(-1), row_if_below_count));
}

// The same for c[a0.x + base], `address` holding a0.x.
template <class I, class Literal>
I RelativeConstantOffset(I address, std::int32_t base, I count, std::int32_t first_row, Literal literal) {
  return ConstantRowOffset(address + literal(base), count, first_row, literal);
}

}  // namespace vs11::semantics
