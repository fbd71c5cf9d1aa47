// The shader debugger for the later models (vs_2_0, vs_2_x, vs_3_0): one vertex through the reference
// engine's program counter (vm/engines/reference_flow.h), every instruction it runs in the order it runs
// them, flow control included. TraceVertex (vm/engines/trace.h) comes here for those programs.
#pragma once

#include <cstddef>

#include "vm/engines/trace.h"

namespace vs11 {

// As TraceVertex, for a program of a later model. Beyond vs_1_1's record each step may carry:
// a note saying what a flow instruction decided (iterations, a branch taken or not, the label called,
// where a ret returns), the aL or a0 lane a relative operand was read through, the b#, i# and p0
// values a condition or a predicated instruction read, and the lanes a predicate turned off.
VertexTrace TraceFlowVertex(const Program& program, const ConstantBank& api_constants, const VertexArrays& inputs,
                            std::size_t vertex, FloatRules rules);

}  // namespace vs11
