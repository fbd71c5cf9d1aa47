// A lowering pass for back ends whose registers hold untyped 32-bit lanes (x86 vector registers): a
// float and its bits are the same register, so bit casts disappear, abs and negate become integer bit
// operations on the float's bits (an and with 0x7FFFFFFF, an xor with the sign bit), and literals
// are shared by their bits whatever their type (0.0f and the int 0 are one vector of zeros). The
// nodes keep their order, each lowered node made where its original was.
#pragma once

#include "vm/ir/graph.h"

namespace vs11::ir {

Graph LowerToBitOperations(const Graph& graph);

}  // namespace vs11::ir
