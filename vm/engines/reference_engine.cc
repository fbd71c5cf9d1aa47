#include "vm/engines/reference_engine.h"

#include <cmath>

#include "vm/core/operands.h"
#include "vm/core/semantics.h"
#include "vm/engines/reference_flow.h"

namespace vs11 {
namespace {

// The reference engine's registers as the shared operand rules (vm/core/operands.h) read and write
// them: one vertex's VertexState, const for reads alone.
template <class State>
struct ReferenceMachine {
  using Float = float;
  using Vec4 = Vec4f;

  const ConstantBank& constants;
  State& state;

  // vs_1_1's a0 is a0.x alone: relative reads use it whatever the lane, writes to other lanes are lost.
  Vec4f ReadConstant(long index, bool relative, int /*lane*/) const {
    return constants.Read(index + (relative ? state.a0 : 0));
  }
  Vec4f ReadInput(long index) const { return state.inputs[static_cast<std::size_t>(index)]; }
  static int TempCount() { return kTempRegisterCount; }
  auto& Temp(long index) const { return state.temps[static_cast<std::size_t>(index)]; }
  auto& Output(int slot) const { return state.outputs[static_cast<std::size_t>(slot)]; }
  void WriteAddress(int lane, float x) const {
    if (lane == 0) state.a0 = AddressFromFloat(x);
  }
  static Vec4f Zero() { return {}; }
};

// Checks at compile time that each row's kernel has the form its ResultKind says.
template <class Semantics>
constexpr bool KernelMatchesKind(ResultKind kind) {
  if constexpr (semantics::HasLane<Semantics, float>) return kind == ResultKind::kComponentwise;
  if constexpr (semantics::HasScalar<Semantics, float>) return kind == ResultKind::kScalar;
  if constexpr (semantics::HasVector<Semantics, float>) return kind == ResultKind::kVector;
  return kind == ResultKind::kDotProduct || kind == ResultKind::kMatrix || kind == ResultKind::kNoResult;
}
template <class Semantics>
constexpr bool HasKernel() {
  return semantics::HasLane<Semantics, float> || semantics::HasScalar<Semantics, float> ||
         semantics::HasVector<Semantics, float>;
}
// A later model's row without a kernel (flow control, setp's comparison, texldl) is run by the
// program counter of vm/engines/reference_flow.cc instead.
#define VS11_CHECK_KERNEL(name, mnemonic, token, shape, kind, slots, mask, default_mask, dot, rows, since) \
  static_assert((ShaderModel::since != ShaderModel::kVs11 && !HasKernel<semantics::name##Semantics>()) ||  \
                    KernelMatchesKind<semantics::name##Semantics>(ResultKind::kind),                      \
                mnemonic);
VS11_OPCODES(VS11_CHECK_KERNEL)
#undef VS11_CHECK_KERNEL

template <FloatRules kRules>
void RunInstructions(const Program& program, const ConstantBank& constants, VertexState& state,
                     InstructionObserver* observer) {
  ReferenceMachine<VertexState> machine{constants, state};
  for (std::size_t i = 0; i < program.instructions.size(); ++i) {
    const Instruction& instruction = program.instructions[i];
    if (observer != nullptr) observer->Before(static_cast<int>(i), state);
    semantics::ExecuteInstruction<kRules>(machine, instruction);
    if (observer != nullptr) observer->After(static_cast<int>(i), state);
  }
}

// The instructions that do something per vertex: nop, dcl and def do nothing there (a def's value is
// in the constant bank from the start), and a program of 100k defs must not cost 100k steps a vertex.
Program ExecutedPart(const Program& program) {
  Program executed;  // instructions only: the source and word positions would not line up
  executed.version = program.version;
  for (const Instruction& instruction : program.instructions) {
    if (instruction.info().kind != ResultKind::kNoResult) executed.instructions.push_back(instruction);
  }
  return executed;
}

class ReferenceEngine final : public Engine {
 public:
  ReferenceEngine(const Program& program, const ConstantBank& api_constants, FloatRules rules)
      : program_(program), executed_(ExecutedPart(program)), constants_(ApplyDefinitions(program, api_constants)),
        written_(WrittenOutputLanes(program)), rules_(rules) {}

  Status SetConstants(const ConstantBank& api_constants) override {
    constants_ = ApplyDefinitions(program_, api_constants);
    return {};
  }

  Status Run(const VertexArrays& inputs, VertexArrays& outputs) override {
    std::vector<int> output_slots = outputs.registers();
    VertexState state;
    for (std::size_t i = 0; i < inputs.count(); ++i) {
      StartVertex(inputs, i, written_, state);
      RunVertex(executed_, constants_, state, nullptr, rules_);
      for (int slot : output_slots) {
        for (int c = 0; c < 4; ++c) outputs.lane(slot, c)[i] = state.outputs[slot][c];
      }
    }
    return {};
  }

 private:
  Program program_;
  Program executed_;
  ConstantBank constants_;
  std::array<WriteMask, kOutputSlotCount> written_;
  FloatRules rules_;
};

}  // namespace

Vec4f ReadRegister(const RegisterRef& reg, int row, const ConstantBank& constants, const VertexState& state) {
  return semantics::ReadRegister(ReferenceMachine<const VertexState>{constants, state}, reg, row);
}

Vec4f FetchSource(const SourceOperand& source, int row, const ConstantBank& constants, const VertexState& state) {
  return semantics::FetchSource(ReferenceMachine<const VertexState>{constants, state}, source, row);
}

void StartVertex(const VertexArrays& inputs, std::size_t vertex, const std::array<WriteMask, kOutputSlotCount>& written,
                 VertexState& state) {
  state.inputs.fill(kDefaultInput);
  for (int reg : inputs.registers()) {
    for (int c = 0; c < 4; ++c) state.inputs[reg][c] = inputs.view(reg, c)[vertex];
  }
  state.temps = {};
  state.a0 = 0;
  for (int slot = 0; slot < kOutputSlotCount; ++slot) {
    state.outputs[slot] = written[slot].bits() ? Vec4f{} : UnwrittenOutputValue(slot);
  }
}

void RunVertex(const Program& program, const ConstantBank& constants, VertexState& state,
               InstructionObserver* observer, FloatRules rules) {
  if (rules == FloatRules::kLegacy) {
    RunInstructions<FloatRules::kLegacy>(program, constants, state, observer);
  } else {
    RunInstructions<FloatRules::kD3d9>(program, constants, state, observer);
  }
}

std::unique_ptr<Engine> MakeReferenceEngine(const Program& program, const ConstantBank& api_constants,
                                            FloatRules rules) {
  // The later models' flow control runs on a program counter of its own; vs_1_1 keeps its loop.
  if (program.model() != ShaderModel::kVs11) return MakeFlowReferenceEngine(program, api_constants, rules);
  return std::make_unique<ReferenceEngine>(program, api_constants, rules);
}

}  // namespace vs11
