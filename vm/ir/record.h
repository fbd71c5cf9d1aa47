// Records a program into the IR (vm/ir/graph.h): runs every instruction's semantics through the one
// opcode dispatch (semantics::ExecuteInstruction, vm/core/operands.h) on handle lane types
// (vm/ir/values.h), which add nodes instead of computing. The nodes therefore hold the reference
// engine's IEEE operations in the reference engine's order, for every back end alike.
//
// What differs between back ends is only where a register's value comes from: a back end supplies
// that as Bindings (the jit: its lane and constant tables, uniform inputs compiled in; the translator:
// GLSL inputs, the constant bank with defs as literals). A relative read, c[a0.x + n], is the same
// for all: one kRelativeRow of the register number a0.x + n, then a kComponent per lane, which each
// back end lowers its own way.
#pragma once

#include <array>
#include <span>

#include "vm/core/float_rules.h"
#include "vm/core/machine.h"
#include "vm/core/program.h"
#include "vm/ir/values.h"

namespace vs11::ir {

class Bindings {
 public:
  virtual ~Bindings() = default;
  // c[index] for 0 <= index (a negative index, or a relative one before a0 is written, reads 0).
  virtual Vec4 ReadConstant(long index) = 0;
  // v[index], index < kInputRegisterCount.
  virtual Vec4 ReadInput(long index) = 0;
  // What output slot `slot` holds before the program writes it (handles with no node: nothing).
  virtual Vec4 InitialOutput(int /*slot*/) { return {}; }
};

// The final values of one recorded vertex (one Bindings).
struct RecordedOutputs {
  std::array<Vec4, kOutputSlotCount> outputs;
};

// Records `program` into `graph`, once per entry of `vertices` (the jit interleaves several vertex
// groups in one loop: their nodes alternate instruction by instruction), products under `rules`.
// Returns each one's output registers after the last instruction.
std::vector<RecordedOutputs> RecordProgram(Graph& graph, const Program& program, std::span<Bindings* const> vertices,
                                           FloatRules rules);

}  // namespace vs11::ir
