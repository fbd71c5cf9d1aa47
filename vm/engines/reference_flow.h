// The reference engine for the later models (vs_2_0, vs_2_x, vs_3_0): one vertex at a time with a
// program counter, a call stack, loop counters and the predicate register. The arithmetic is the shared
// kernels of vm/core/semantics.h; vs_1_1 programs never come here (reference_engine.cc keeps its own
// straight-line loop for them).
#pragma once

#include <array>
#include <cstddef>
#include <memory>
#include <optional>

#include "vm/core/machine.h"
#include "vm/core/static_flow.h"  // kMaxLoopCount

namespace vs11 {

inline constexpr int kFlowTempCount = RegisterCount(RegisterFile::kTemp, ShaderModel::kVs30);
inline constexpr int kFlowInputCount = RegisterCount(RegisterFile::kInput, ShaderModel::kVs30);

// One vertex's registers in the later models: 32 temporaries, a0 as four lanes, aL and p0.
struct FlowState {
  std::array<Vec4f, kFlowInputCount> inputs{};
  std::array<Vec4f, kFlowTempCount> temps{};
  std::array<Vec4f, kOutputSlotCount> outputs{};
  std::array<int, 4> a0{};
  int aL = 0;
  std::array<bool, 4> p0{};
};

// Vertex `vertex` of `inputs` loaded into `state` as the engine starts it (unsupplied inputs
// kDefaultInput, outputs the program never writes UnwrittenOutputValue: `written` =
// WrittenOutputLanes(program)).
void StartFlowVertex(const VertexArrays& inputs, std::size_t vertex,
                     const std::array<WriteMask, kOutputSlotCount>& written, FlowState& state);

// What the engine reads: the register a (relative) operand names, through aL or a0's lane; its value
// (row > 0: the next registers of a matrix operand; outside its file: 0); the source operand swizzled,
// _abs applied and negated.
long FlowAddress(const RegisterRef& reg, const FlowState& state);
Vec4f FlowReadRegister(const RegisterRef& reg, int row, const ConstantBank& constants, const FlowState& state);
Vec4f FlowFetch(const SourceOperand& source, int row, const ConstantBank& constants, const FlowState& state);
// The value of the condition of if b#/p0.c, callnz's second source or breakp, `!` applied.
bool FlowCondition(const SourceOperand& source, const ConstantBank& constants, const FlowState& state);

// Whether lane `lane` of a predicated instruction is on: its predicate's (swizzled, negated) p0 lane.
bool FlowPredicateLane(const Instruction& instruction, int lane, const FlowState& state);

// The register a destination writes: a temporary, or the output slot it stands for (vs_3_0: o# through
// its dcl, o#[aL] resolved); null for any other (a0 and p0 are written apart) or out of range.
template <class State>  // FlowState or const FlowState
auto* FlowTarget(const RegisterRef& reg, ShaderModel model,
                 const std::array<std::optional<int>, kOutputRegisterCountVs30>& declared_outputs, State& state) {
  using Pointer = decltype(&state.temps[0]);
  const long index = FlowAddress(reg, state);
  if (reg.file == RegisterFile::kTemp) {
    return index >= 0 && index < kFlowTempCount ? &state.temps[static_cast<std::size_t>(index)] : Pointer{};
  }
  std::optional<int> slot;
  if (model == ShaderModel::kVs30) {
    if (reg.file == RegisterFile::kTexCoordOut && index >= 0 && index < kOutputRegisterCountVs30) {
      slot = declared_outputs[static_cast<std::size_t>(index)];
    }
  } else {
    slot = OutputSlotOf(reg);
  }
  return slot ? &state.outputs[static_cast<std::size_t>(*slot)] : Pointer{};
}

// Sees every instruction the walk runs, flow control included, with the state before it and after it
// and the instruction that runs next (-1: the program ends). It only observes (the debugger,
// vm/engines/flow_trace.cc).
class FlowObserver {
 public:
  virtual ~FlowObserver() = default;
  virtual void Before(int instruction_index, const FlowState& state) = 0;
  virtual void After(int instruction_index, int next_index, const FlowState& state) = 0;
};

// Runs `program` (a later model; `constants` = ModelConstants(program, api)) on one vertex, its
// products under `rules`.
void RunFlowVertex(const Program& program, const ConstantBank& constants, FlowState& state, FlowObserver* observer,
                   FloatRules rules);

// `program` must be of a later model and pass EngineRefusal(program, kLaterModelEngine).
std::unique_ptr<Engine> MakeFlowReferenceEngine(const Program& program, const ConstantBank& api_constants,
                                                FloatRules rules);

}  // namespace vs11
