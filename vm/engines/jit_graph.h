// The jit's graph: the program recorded into the IR (vm/ir/record.h) with the batch engine's tables
// as its registers, its relative reads lowered to gathers from that table, and lowered to bit
// operations (vm/ir/lower_bits.h), as the emitter
// (vm/engines/jit_compiler.cc) turns it into machine code.
#pragma once

#include <cstdint>
#include <span>

#include "vm/core/program.h"
#include "vm/engines/jit_compiler.h"
#include "vm/ir/graph.h"

namespace vs11::jit {

// Input and store nodes name a lane of the batch engine's lane table (vm/engines/batch_plan.h) and,
// above kGroupShift, which of the loop's vertex groups (a vector of vertices each) they belong to.
// Constant nodes name a float of its constant table; gathers read one at a computed float offset.
constexpr int kGroupShift = 16;
constexpr std::uint32_t kLaneMask = (1u << kGroupShift) - 1;

// One vertex group per `groups`, interleaved instruction by instruction; `uniform_inputs` are
// compiled in as literals; products follow `rules`. Every output lane the program writes is stored
// once per group, the groups' stores of a lane side by side.
ir::Graph RecordLoopBody(const Program& program, int groups, std::span<const UniformInput> uniform_inputs,
                         FloatRules rules);

}  // namespace vs11::jit
