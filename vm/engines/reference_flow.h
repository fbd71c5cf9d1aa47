// The reference engine for the later models (vs_2_0, vs_2_x, vs_3_0): one vertex at a time with a
// program counter, a call stack, loop counters and the predicate register. The arithmetic is the shared
// kernels of vm/core/semantics.h; vs_1_1 programs never come here (reference_engine.cc keeps its own
// straight-line loop for them).
#pragma once

#include <memory>

#include "vm/core/machine.h"
#include "vm/core/static_flow.h"  // kMaxLoopCount

namespace vs11 {

// `program` must be of a later model and pass EngineRefusal(program, kLaterModelEngine).
std::unique_ptr<Engine> MakeFlowReferenceEngine(const Program& program, const ConstantBank& api_constants,
                                                FloatRules rules);

}  // namespace vs11
