#include "vm/translate/shader_graph.h"

#include <bit>
#include <limits>
#include <tuple>

#include "vm/core/operands.h"
#include "vm/core/semantics.h"

namespace vs11::translate {
namespace {

// Records nodes, sharing identical ones. TraceShader sets `recording` for its duration (one trace
// at a time per thread).
class Recorder {
 public:
  explicit Recorder(ShaderGraph& graph) : graph_(graph) {}
  int Add(NodeOp op, ValueType type, std::array<int, 3> args = {kNoNode, kNoNode, kNoNode}, std::uint32_t immediate = 0) {
    const auto key = std::make_tuple(op, args, immediate);
    if (const auto it = existing_.find(key); it != existing_.end()) return it->second;
    graph_.nodes.push_back({op, type, args, immediate, instruction_});
    const int id = static_cast<int>(graph_.nodes.size()) - 1;
    existing_.emplace(key, id);
    return id;
  }
  void set_instruction(int index) { instruction_ = index; }

 private:
  ShaderGraph& graph_;
  std::map<std::tuple<NodeOp, std::array<int, 3>, std::uint32_t>, int> existing_;
  int instruction_ = -1;
};

thread_local Recorder* recording = nullptr;

int Record(NodeOp op, ValueType type, int a = kNoNode, int b = kNoNode, int c = kNoNode, std::uint32_t immediate = 0) {
  return recording->Add(op, type, {a, b, c}, immediate);
}

// The lane types semantics.h is instantiated with: handles to nodes, typed so that float, integer and
// bool operations resolve as they do for float, int32 and bool.
struct Float {
  int id = kNoNode;
};
struct Int {
  int id = kNoNode;
};
struct Bool {
  int id = kNoNode;
};

Float MakeFloat(NodeOp op, int a = kNoNode, int b = kNoNode, int c = kNoNode, std::uint32_t immediate = 0) {
  return {Record(op, ValueType::kFloat, a, b, c, immediate)};
}
Int MakeInt(NodeOp op, int a = kNoNode, int b = kNoNode, std::uint32_t immediate = 0) {
  return {Record(op, ValueType::kInt, a, b, kNoNode, immediate)};
}
Bool MakeBool(NodeOp op, int a, int b) { return {Record(op, ValueType::kBool, a, b)}; }

Float operator+(Float a, Float b) { return MakeFloat(NodeOp::kAdd, a.id, b.id); }
Float operator-(Float a, Float b) { return MakeFloat(NodeOp::kSub, a.id, b.id); }
Float operator*(Float a, Float b) { return MakeFloat(NodeOp::kMul, a.id, b.id); }
Float operator/(Float a, Float b) { return MakeFloat(NodeOp::kDiv, a.id, b.id); }
Bool operator<(Float a, Float b) { return MakeBool(NodeOp::kLess, a.id, b.id); }
Bool operator>(Float a, Float b) { return MakeBool(NodeOp::kGreater, a.id, b.id); }
Bool operator>=(Float a, Float b) { return MakeBool(NodeOp::kGreaterEqual, a.id, b.id); }
Bool operator==(Float a, Float b) { return MakeBool(NodeOp::kEqual, a.id, b.id); }
[[maybe_unused]] Bool operator>(Int a, Int b) { return MakeBool(NodeOp::kIntGreater, a.id, b.id); }
Int operator+(Int a, Int b) { return MakeInt(NodeOp::kIntAdd, a.id, b.id); }
Int operator-(Int a, Int b) { return MakeInt(NodeOp::kIntSub, a.id, b.id); }
Int operator&(Int a, Int b) { return MakeInt(NodeOp::kIntAnd, a.id, b.id); }
Int operator|(Int a, Int b) { return MakeInt(NodeOp::kIntOr, a.id, b.id); }

Float Constant(Float, float value) {
  return MakeFloat(NodeOp::kFloatLiteral, kNoNode, kNoNode, kNoNode, std::bit_cast<std::uint32_t>(value));
}
Float LiteralBits(std::uint32_t bits) { return MakeFloat(NodeOp::kFloatLiteral, kNoNode, kNoNode, kNoNode, bits); }
Int ConstantInt(Float, std::int32_t value) {
  return MakeInt(NodeOp::kIntLiteral, kNoNode, kNoNode, static_cast<std::uint32_t>(value));
}
Int BitsOf(Float x) { return MakeInt(NodeOp::kBitsOf, x.id); }
Float FloatFromBits(Int x) { return MakeFloat(NodeOp::kFloatFromBits, x.id); }
Float Floor(Float x) { return MakeFloat(NodeOp::kFloor, x.id); }
Float Sqrt(Float x) { return MakeFloat(NodeOp::kSqrt, x.id); }
Float Abs(Float x) { return MakeFloat(NodeOp::kAbs, x.id); }
Float Negate(Float x) { return MakeFloat(NodeOp::kNegate, x.id); }
Bool IsNaN(Float x) { return {Record(NodeOp::kIsNaN, ValueType::kBool, x.id)}; }
Float IfThenElse(Bool condition, Float yes, Float no) { return MakeFloat(NodeOp::kSelect, condition.id, yes.id, no.id); }
Int ToInt(Float x) { return MakeInt(NodeOp::kToInt, x.id); }
Float ToFloat(Int x) { return MakeFloat(NodeOp::kToFloat, x.id); }
template <int kBits>
Int ShiftLeft(Int x) {
  return MakeInt(NodeOp::kShiftLeft, x.id, kNoNode, kBits);
}
template <int kBits>
Int ShiftRight(Int x) {
  return MakeInt(NodeOp::kShiftRight, x.id, kNoNode, kBits);
}

using Vec4F = semantics::Vec4<Float>;

Vec4F Literal(const Vec4f& value) {
  Vec4F result;
  for (int c = 0; c < 4; ++c) result[c] = Constant(Float{}, value[c]);
  return result;
}

// The machine interface of vm/core/operands.h, over nodes.
class Tracer {
 public:
  using Float = translate::Float;
  using Vec4 = Vec4F;

  explicit Tracer(ShaderGraph& graph) : graph_(graph) {
    for (auto& temp : temps_) temp = Zero();  // temporaries start at 0, as in the engines
    for (int slot = 0; slot < kOutputSlotCount; ++slot) {
      outputs_[slot] = graph.written[slot].bits() != 0 ? Zero() : Literal(UnwrittenOutputValue(slot));
    }
  }

  Vec4F ReadConstant(long index, bool relative) const {
    if (!relative || !address_written_) return StaticConstant(index);  // a0 is 0 until written
    const Int row = address_ + ConstantInt(Float{}, static_cast<std::int32_t>(index));
    const int vector = Record(NodeOp::kRelativeRow, ValueType::kVec4, row.id);
    Vec4F value;
    for (int c = 0; c < 4; ++c) value[c] = MakeFloat(NodeOp::kComponent, vector, kNoNode, kNoNode, static_cast<std::uint32_t>(c));
    return value;
  }
  Vec4F ReadInput(long index) const {
    graph_.inputs_read[static_cast<std::size_t>(index)] = true;
    Vec4F value;
    for (int c = 0; c < 4; ++c) value[c] = MakeFloat(NodeOp::kInput, kNoNode, kNoNode, kNoNode, static_cast<std::uint32_t>(index * 4 + c));
    return value;
  }
  Vec4F& Temp(long index) { return temps_[static_cast<std::size_t>(index)]; }
  const Vec4F& Temp(long index) const { return temps_[static_cast<std::size_t>(index)]; }
  Vec4F& Output(int slot) { return outputs_[static_cast<std::size_t>(slot)]; }
  void WriteAddress(Float x) {
    address_ = semantics::AddressFromFloat(x);
    address_written_ = true;
  }
  static Vec4F Zero() { return Literal({}); }

  const std::array<Vec4F, kOutputSlotCount>& outputs() const { return outputs_; }

 private:
  Vec4F StaticConstant(long index) const {
    if (index < 0 || index >= graph_.constant_count) return Zero();
    if (const auto def = graph_.definitions.find(static_cast<int>(index)); def != graph_.definitions.end()) {
      Vec4F value;
      for (int c = 0; c < 4; ++c) value[c] = LiteralBits(def->second[c]);
      return value;
    }
    Vec4F value;
    for (int c = 0; c < 4; ++c) value[c] = MakeFloat(NodeOp::kConstant, kNoNode, kNoNode, kNoNode, static_cast<std::uint32_t>(index * 4 + c));
    return value;
  }

  ShaderGraph& graph_;
  std::array<Vec4F, kTempRegisterCount> temps_{};
  std::array<Vec4F, kOutputSlotCount> outputs_{};
  Int address_;
  bool address_written_ = false;
};

template <FloatRules kRules>
void TraceInstruction(Tracer& tracer, const Instruction& instruction) {
  switch (instruction.opcode) {
#define VS11_TRANSLATE_TRACE_CASE(name, ...) \
  case Opcode::k##name: semantics::Execute<semantics::name##Semantics, kRules>(tracer, instruction); break;
    VS11_OPCODES(VS11_TRANSLATE_TRACE_CASE)
#undef VS11_TRANSLATE_TRACE_CASE
  }
}

}  // namespace

ShaderGraph TraceShader(const Program& program, int constant_count, FloatRules rules) {
  ShaderGraph graph;
  graph.constant_count = constant_count;
  graph.written = WrittenOutputLanes(program);
  for (const Instruction& instruction : program.instructions) {
    const int index = instruction.dest.reg.index;
    if (instruction.opcode == Opcode::kDef && index >= 0 && index < constant_count) graph.definitions[index] = instruction.def_bits;
  }
  Recorder recorder(graph);
  recording = &recorder;
  Tracer tracer(graph);
  for (std::size_t i = 0; i < program.instructions.size(); ++i) {
    recorder.set_instruction(static_cast<int>(i));
    if (rules == FloatRules::kLegacy) {
      TraceInstruction<FloatRules::kLegacy>(tracer, program.instructions[i]);
    } else {
      TraceInstruction<FloatRules::kD3d9>(tracer, program.instructions[i]);
    }
  }
  for (int slot = 0; slot < kOutputSlotCount; ++slot) {
    for (int c = 0; c < 4; ++c) graph.outputs[slot][c] = tracer.outputs()[slot][c].id;
  }
  recording = nullptr;
  return graph;
}

std::vector<bool> LiveNodes(const ShaderGraph& graph) {
  std::vector<bool> live(graph.nodes.size(), false);
  for (const auto& slot : graph.outputs) {
    for (int id : slot) live[static_cast<std::size_t>(id)] = true;
  }
  // Arguments always come before their users: one backward pass suffices.
  for (std::size_t n = graph.nodes.size(); n-- > 0;) {
    if (!live[n]) continue;
    for (int arg : graph.nodes[n].args) {
      if (arg != kNoNode) live[static_cast<std::size_t>(arg)] = true;
    }
  }
  return live;
}

}  // namespace vs11::translate
