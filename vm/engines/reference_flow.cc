#include "vm/engines/reference_flow.h"

#include <algorithm>
#include <optional>
#include <type_traits>
#include <utility>
#include <vector>

#include "vm/core/operands.h"
#include "vm/core/semantics.h"
#include "vm/core/static_flow.h"
#include "vm/core/texture_sampling.h"
#include "vm/engines/reference_engine.h"

namespace vs11 {
namespace {

constexpr int kTemps = kFlowTempCount;
constexpr int kInputs = kFlowInputCount;

template <FloatRules kRules>
class FlowInterpreter {
 public:
  FlowInterpreter(const Program& program, const ControlTable& control, const ConstantBank& constants,
                  const std::array<std::optional<int>, kOutputRegisterCountVs30>& declared_outputs, FlowState& state)
      : program_(program), control_(control), constants_(constants), declared_outputs_(declared_outputs),
        state_(state), model_(program.model()) {}

  void Run(FlowObserver* observer = nullptr) {
    const int n = static_cast<int>(program_.instructions.size());
    FlowWalk<FlowInterpreter> walk(program_, control_, *this, state_.aL);
    int pc = 0;
    while (pc >= 0 && pc < n) {
      if (observer == nullptr) {
        pc = walk.Step(pc);
        continue;
      }
      observer->Before(pc, state_);
      const int next = walk.Step(pc);
      observer->After(pc, next >= 0 && next < n ? next : -1, state_);
      pc = next;
    }
  }

 private:
  friend class FlowWalk<FlowInterpreter>;

  Vec4i Integer(int index) const { return constants_.ReadInteger(index); }

  bool Condition(const SourceOperand& source) const { return FlowCondition(source, constants_, state_); }

  // if_comp, break_comp: the x lanes of the two (replicate-swizzled) sources.
  bool Comparison(const Instruction& instruction) const {
    return semantics::Compare(instruction.comparison, Fetch(instruction.sources[0], 0)[0],
                              Fetch(instruction.sources[1], 0)[0]) != 0.0f;
  }

  long AddressOf(const RegisterRef& reg) const { return FlowAddress(reg, state_); }
  Vec4f Fetch(const SourceOperand& source, int row) const { return FlowFetch(source, row, constants_, state_); }

  template <class Semantics>
  std::optional<Vec4f> Compute(const Instruction& instruction) const {
    const OpcodeInfo& info = instruction.info();
    std::array<Vec4f, 3> src{};
    for (int s = 0; s < std::min(SourceCount(info, model_), 3); ++s) src[s] = Fetch(instruction.sources[s], 0);
    Vec4f result{};
    if constexpr (std::is_same_v<Semantics, semantics::TexldlSemantics>) {
      result = semantics::Texldl(BankTextures{constants_}, instruction, src[0]);
    } else if constexpr (semantics::HasLane<Semantics, float>) {
      for (int lane = 0; lane < 4; ++lane) {
        result[lane] = semantics::RunLane<kRules, Semantics>(src[0][lane], src[1][lane], src[2][lane]);
      }
    } else if constexpr (semantics::HasScalar<Semantics, float>) {
      result.fill(Semantics::Scalar(src[0][3]));
    } else if constexpr (semantics::HasVector<Semantics, float>) {
      result = semantics::RunVector<kRules, Semantics>(src[0], src[1]);
    } else if (info.kind == ResultKind::kDotProduct) {
      result.fill(semantics::DotOfWidth<kRules>(info.dot_width, src[0], src[1]));
    } else if (info.kind == ResultKind::kMatrix) {
      for (int row = 0; row < info.matrix_rows; ++row) {
        result[row] = semantics::DotOfWidth<kRules>(info.dot_width, src[0],
                                                    Fetch(instruction.sources[OpcodeInfo::kMatrixSource], row));
      }
    } else {
      return std::nullopt;  // dcl, def, defi, defb, nop
    }
    return result;
  }

  std::optional<Vec4f> ComputeAny(const Instruction& instruction) const {
    switch (instruction.opcode) {
#define VS11_FLOW_COMPUTE_CASE(name, ...) \
  case Opcode::k##name: return Compute<semantics::name##Semantics>(instruction);
      VS11_OPCODES(VS11_FLOW_COMPUTE_CASE)
#undef VS11_FLOW_COMPUTE_CASE
    }
    return std::nullopt;
  }

  // The lanes an instruction writes: its mask, less what the opcode never writes (crs's w, sincos's z
  // and w, a matrix's missing rows), less the lanes a predicate turns off.
  WriteMask LanesWritten(const Instruction& instruction) const {
    std::uint8_t lanes = semantics::LanesWritten(instruction).bits();
    if (instruction.predicated) {
      for (int lane = 0; lane < 4; ++lane) {
        if (!FlowPredicateLane(instruction, lane, state_)) lanes &= static_cast<std::uint8_t>(~(1u << lane));
      }
    }
    return WriteMask(lanes);
  }

  Vec4f* Target(const RegisterRef& reg) { return FlowTarget(reg, model_, declared_outputs_, state_); }

  void Execute(const Instruction& instruction) {
    if (!instruction.info().is_executable()) return;
    const WriteMask lanes = LanesWritten(instruction);
    if (instruction.opcode == Opcode::kSetp) {
      const Vec4f a = Fetch(instruction.sources[0], 0), b = Fetch(instruction.sources[1], 0);
      for (int lane = 0; lane < 4; ++lane) {
        if (lanes.has(lane)) state_.p0[lane] = semantics::Compare(instruction.comparison, a[lane], b[lane]) != 0.0f;
      }
      return;
    }
    std::optional<Vec4f> result = ComputeAny(instruction);
    if (!result) return;
    if (instruction.dest.saturate) {
      for (float& v : *result) v = semantics::Saturate(v);
    }
    if (instruction.dest.reg.file == RegisterFile::kAddress) {
      // mova's value is already rounded; vs_1_1's mov a0 floors (AddressFromFloat), and on integers
      // the two agree.
      for (int lane = 0; lane < 4; ++lane) {
        if (lanes.has(lane)) state_.a0[lane] = semantics::AddressFromFloat((*result)[lane]);
      }
      return;
    }
    if (Vec4f* target = Target(instruction.dest.reg)) {
      for (int lane = 0; lane < 4; ++lane) {
        if (lanes.has(lane)) (*target)[lane] = (*result)[lane];
      }
    }
  }

  const Program& program_;
  const ControlTable& control_;
  const ConstantBank& constants_;
  const std::array<std::optional<int>, kOutputRegisterCountVs30>& declared_outputs_;
  FlowState& state_;
  const ShaderModel model_;
};

class FlowReferenceEngine final : public Engine {
 public:
  FlowReferenceEngine(const Program& program, const ConstantBank& api_constants, FloatRules rules)
      : program_(program), control_(BuildControlTable(program)), constants_(ModelConstants(program, api_constants)),
        written_(WrittenOutputLanes(program)), declared_outputs_(DeclaredOutputSlots(program)), rules_(rules) {}

  Status SetConstants(const ConstantBank& api_constants) override {
    constants_ = ModelConstants(program_, api_constants);
    return {};
  }

  Status Run(const VertexArrays& inputs, VertexArrays& outputs) override {
    const std::vector<int> output_slots = outputs.registers();
    FlowState state;
    for (std::size_t i = 0; i < inputs.count(); ++i) {
      StartFlowVertex(inputs, i, written_, state);
      if (rules_ == FloatRules::kLegacy) {
        FlowInterpreter<FloatRules::kLegacy>(program_, control_, constants_, declared_outputs_, state).Run();
      } else {
        FlowInterpreter<FloatRules::kD3d9>(program_, control_, constants_, declared_outputs_, state).Run();
      }
      for (int slot : output_slots) {
        for (int c = 0; c < 4; ++c) outputs.lane(slot, c)[i] = state.outputs[static_cast<std::size_t>(slot)][c];
      }
    }
    return {};
  }

 private:
  Program program_;
  ControlTable control_;
  ConstantBank constants_;
  std::array<WriteMask, kOutputSlotCount> written_;
  std::array<std::optional<int>, kOutputRegisterCountVs30> declared_outputs_;
  FloatRules rules_;
};

}  // namespace

void StartFlowVertex(const VertexArrays& inputs, std::size_t vertex,
                     const std::array<WriteMask, kOutputSlotCount>& written, FlowState& state) {
  state = FlowState{};
  state.inputs.fill(kDefaultInput);
  for (int reg : inputs.registers()) {
    if (reg >= kInputs) continue;
    for (int c = 0; c < 4; ++c) state.inputs[static_cast<std::size_t>(reg)][c] = inputs.view(reg, c)[vertex];
  }
  for (int slot = 0; slot < kOutputSlotCount; ++slot) {
    state.outputs[static_cast<std::size_t>(slot)] = written[slot].bits() ? Vec4f{} : UnwrittenOutputValue(slot);
  }
}

long FlowAddress(const RegisterRef& reg, const FlowState& state) {
  if (!reg.relative) return reg.index;
  const int offset = reg.address.file == RegisterFile::kLoop ? state.aL : state.a0[reg.address.swizzle_bits & 3];
  return static_cast<long>(reg.index) + offset;
}

Vec4f FlowReadRegister(const RegisterRef& reg, int row, const ConstantBank& constants, const FlowState& state) {
  const long index = FlowAddress(reg, state) + row;
  switch (reg.file) {
    case RegisterFile::kConst: return constants.Read(index);
    case RegisterFile::kTemp: return index >= 0 && index < kTemps ? state.temps[static_cast<std::size_t>(index)] : Vec4f{};
    case RegisterFile::kInput: return index >= 0 && index < kInputs ? state.inputs[static_cast<std::size_t>(index)] : Vec4f{};
    default: return {};
  }
}

// The register, swizzled, then _abs, then negated (§3.1's order, with vs_3_0's _abs before the sign).
Vec4f FlowFetch(const SourceOperand& source, int row, const ConstantBank& constants, const FlowState& state) {
  const Vec4f base = FlowReadRegister(source.reg, row, constants, state);
  Vec4f value;
  for (int lane = 0; lane < 4; ++lane) {
    float v = base[static_cast<std::size_t>(source.swizzle[lane])];
    if (source.absolute) v = semantics::Abs(v);
    value[static_cast<std::size_t>(lane)] = source.negate ? semantics::Negate(v) : v;
  }
  return value;
}

bool FlowPredicateLane(const Instruction& instruction, int lane, const FlowState& state) {
  return state.p0[static_cast<std::size_t>(instruction.predicate.swizzle[lane])] != instruction.predicate.logical_not;
}

bool FlowCondition(const SourceOperand& source, const ConstantBank& constants, const FlowState& state) {
  bool value = false;
  if (source.reg.file == RegisterFile::kConstBool) value = constants.ReadBoolean(source.reg.index);
  if (source.reg.file == RegisterFile::kPredicate) value = state.p0[static_cast<std::size_t>(source.swizzle[0])];
  return value != source.logical_not;
}

void RunFlowVertex(const Program& program, const ConstantBank& constants, FlowState& state, FlowObserver* observer,
                   FloatRules rules) {
  const ControlTable control = BuildControlTable(program);
  const auto declared_outputs = DeclaredOutputSlots(program);
  if (rules == FloatRules::kLegacy) {
    FlowInterpreter<FloatRules::kLegacy>(program, control, constants, declared_outputs, state).Run(observer);
  } else {
    FlowInterpreter<FloatRules::kD3d9>(program, control, constants, declared_outputs, state).Run(observer);
  }
}

std::unique_ptr<Engine> MakeFlowReferenceEngine(const Program& program, const ConstantBank& api_constants,
                                                FloatRules rules) {
  return std::make_unique<FlowReferenceEngine>(program, api_constants, rules);
}

}  // namespace vs11
