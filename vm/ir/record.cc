#include "vm/ir/record.h"

#include <vector>

#include "vm/core/operands.h"

namespace vs11::ir {
namespace {

thread_local Graph* recording = nullptr;

// The machine interface of vm/core/operands.h over graph values: temporaries and a0 are kept here,
// everything a back end lays out its own way is asked of its Bindings.
class RecordingMachine {
 public:
  using Float = ir::Float;
  using Vec4 = ir::Vec4;

  RecordingMachine(Bindings& bindings, const Program& program)
      : bindings_(bindings),
        temp_count_(semantics::TempCountOf(program)),
        address_lanes_(semantics::AddressLaneCountOf(program)) {
    for (auto& temp : temps_) temp = Zero();  // temporaries start at 0, as in the engines
    for (int slot = 0; slot < kOutputSlotCount; ++slot) outputs_[slot] = bindings.InitialOutput(slot);
  }

  Vec4 ReadConstant(long index, bool relative, int lane) const {
    if (lane >= address_lanes_) lane = 0;  // vs_1_1: a0.x whatever the lane
    if (relative && address_written_[lane]) {
      return ReadRelativeRow(address_[lane] + LiteralInt(static_cast<std::int32_t>(index)));
    }
    if (index < 0) return Zero();  // a0 is 0 until written
    return bindings_.ReadConstant(index);
  }
  static Vec4 ReadRelativeRow(Int register_number) {
    const int row = Record(Op::kRelativeRow, Type::kVec4, {register_number.id});
    Vec4 value;
    for (int c = 0; c < 4; ++c) value[c] = RecordFloat(Op::kComponent, {row}, static_cast<std::uint32_t>(c));
    return value;
  }
  Vec4 ReadInput(long index) const { return bindings_.ReadInput(index); }
  int TempCount() const { return temp_count_; }
  Vec4& Temp(long index) { return temps_[static_cast<std::size_t>(index)]; }
  const Vec4& Temp(long index) const { return temps_[static_cast<std::size_t>(index)]; }
  Vec4& Output(int slot) { return outputs_[static_cast<std::size_t>(slot)]; }
  void WriteAddress(int lane, Float x) {
    if (lane >= address_lanes_) return;
    address_[lane] = semantics::AddressFromFloat(x);
    address_value_[lane] = x;
    address_written_[lane] = true;
  }
  Float AddressValue(int lane) const { return address_written_[lane] ? address_value_[lane] : Zero()[0]; }
  // Predicate registers (only the straight-line form of a later model's flow has them): 0 until written.
  Vec4& Predicate(long index) {
    if (static_cast<std::size_t>(index) >= predicates_.size()) predicates_.resize(static_cast<std::size_t>(index) + 1, Zero());
    return predicates_[static_cast<std::size_t>(index)];
  }
  Vec4 Predicate(long index) const {
    return static_cast<std::size_t>(index) < predicates_.size() ? predicates_[static_cast<std::size_t>(index)] : Zero();
  }
  // An output lane no instruction has written reads 0 under a predicated write, as in the reference.
  static Float Written(Float old) { return old.id == kNoNode ? Zero()[0] : old; }
  static Vec4 Zero() {
    const Float zero = Constant(Float{}, 0.0f);
    return {zero, zero, zero, zero};
  }

  void Execute(const Instruction& instruction, FloatRules rules) {
    if (rules == FloatRules::kLegacy) {
      semantics::ExecuteInstruction<FloatRules::kLegacy>(*this, instruction);
    } else {
      semantics::ExecuteInstruction<FloatRules::kD3d9>(*this, instruction);
    }
  }
  const std::array<Vec4, kOutputSlotCount>& outputs() const { return outputs_; }

 private:
  Bindings& bindings_;
  const int temp_count_;
  const int address_lanes_;
  std::array<Vec4, semantics::kLaterModelTempCount> temps_{};
  std::array<Vec4, kOutputSlotCount> outputs_{};
  std::array<Int, 4> address_{};
  std::array<Float, 4> address_value_{};
  std::array<bool, 4> address_written_{};
  std::vector<Vec4> predicates_;
};

}  // namespace

Recording::Recording(Graph& graph) { recording = &graph; }
Recording::~Recording() { recording = nullptr; }
Graph& Recording::graph() { return *recording; }

int Record(Op op, Type type, Operands args, std::uint32_t immediate) { return recording->Add(op, type, args, immediate); }

std::vector<RecordedOutputs> RecordProgram(Graph& graph, const Program& program, std::span<Bindings* const> vertices,
                                           FloatRules rules) {
  const Recording recording_scope(graph);
  std::vector<RecordingMachine> machines;
  machines.reserve(vertices.size());
  for (Bindings* bindings : vertices) machines.emplace_back(*bindings, program);
  for (std::size_t i = 0; i < program.instructions.size(); ++i) {
    graph.set_instruction(static_cast<int>(i));
    for (RecordingMachine& machine : machines) machine.Execute(program.instructions[i], rules);
  }
  std::vector<RecordedOutputs> outputs;
  for (const RecordingMachine& machine : machines) outputs.push_back({machine.outputs()});
  return outputs;
}

}  // namespace vs11::ir
