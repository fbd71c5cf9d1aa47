#include "vm/engines/jit_graph.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <limits>
#include <optional>

#include "vm/core/constant_gather.h"
#include "vm/core/machine.h"
#include "vm/core/operands.h"
#include "vm/core/semantics.h"
#include "vm/engines/batch_plan.h"

namespace vs11::jit {
namespace {

// The graph being traced (TraceProgram sets it for its duration; tracing is single-threaded per call).
thread_local Graph* tracing = nullptr;

int Trace(Op op, int a = kNoArg, int b = kNoArg, int c = kNoArg, std::uint32_t immediate = 0) {
  return tracing->Add(op, {a, b, c}, immediate);
}

// The lane types vm/core/semantics.h is instantiated with: handles to graph nodes, typed so that float,
// integer and mask operations resolve as they do for float/int32/bool and Highway vectors.
struct Float {
  int id = kNoArg;
};
struct Int {
  int id = kNoArg;
};
struct Mask {
  int id = kNoArg;
};

inline Float operator+(Float a, Float b) { return {Trace(Op::kAdd, a.id, b.id)}; }
inline Float operator-(Float a, Float b) { return {Trace(Op::kSub, a.id, b.id)}; }
inline Float operator*(Float a, Float b) { return {Trace(Op::kMul, a.id, b.id)}; }
inline Float operator/(Float a, Float b) { return {Trace(Op::kDiv, a.id, b.id)}; }
inline Mask operator<(Float a, Float b) { return {Trace(Op::kLess, a.id, b.id)}; }
inline Mask operator>(Float a, Float b) { return {Trace(Op::kGreater, a.id, b.id)}; }
inline Mask operator>=(Float a, Float b) { return {Trace(Op::kGreaterEqual, a.id, b.id)}; }
inline Mask operator==(Float a, Float b) { return {Trace(Op::kEqual, a.id, b.id)}; }
inline Int operator+(Int a, Int b) { return {Trace(Op::kIntAdd, a.id, b.id)}; }
inline Int operator-(Int a, Int b) { return {Trace(Op::kIntSub, a.id, b.id)}; }
inline Int operator&(Int a, Int b) { return {Trace(Op::kAnd, a.id, b.id)}; }
inline Int operator|(Int a, Int b) { return {Trace(Op::kOr, a.id, b.id)}; }

inline Float Constant(Float, float value) { return {Trace(Op::kLiteral, kNoArg, kNoArg, kNoArg, std::bit_cast<std::uint32_t>(value))}; }
inline Int ConstantInt(Float, std::int32_t value) {
  return {Trace(Op::kLiteral, kNoArg, kNoArg, kNoArg, static_cast<std::uint32_t>(value))};
}
inline Int BitsOf(Float x) { return {x.id}; }
inline Float FloatFromBits(Int x) { return {x.id}; }
inline Float Floor(Float x) { return {Trace(Op::kFloor, x.id)}; }
inline Float Sqrt(Float x) { return {Trace(Op::kSqrt, x.id)}; }
inline Float Abs(Float x) { return FloatFromBits(BitsOf(x) & ConstantInt(x, 0x7FFFFFFF)); }
inline Mask IsNaN(Float x) { return {Trace(Op::kUnordered, x.id, x.id)}; }
inline Float IfThenElse(Mask condition, Float yes, Float no) { return {Trace(Op::kSelect, condition.id, yes.id, no.id)}; }
inline Int ToInt(Float x) { return {Trace(Op::kToInt, x.id)}; }
inline Float ToFloat(Int x) { return {Trace(Op::kToFloat, x.id)}; }
template <int kBits>
Int ShiftLeft(Int x) { return {Trace(Op::kShiftLeft, x.id, kNoArg, kNoArg, kBits)}; }
template <int kBits>
Int ShiftRight(Int x) { return {Trace(Op::kShiftRight, x.id, kNoArg, kNoArg, kBits)}; }
inline Mask operator>(Int a, Int b) { return {Trace(Op::kIntGreater, a.id, b.id)}; }
inline Int IfThenElseZero(Mask condition, Int value) { return {Trace(Op::kSelectZero, condition.id, value.id)}; }
inline Int LiteralInt(std::int32_t value) { return ConstantInt(Float{}, value); }

// -x as the reference engine negates: the sign bit flipped, NaNs included.
inline Float Negate(Float x) {
  return {Trace(Op::kXor, x.id, ConstantInt(x, std::numeric_limits<std::int32_t>::min()).id)};
}

using Vec4F = semantics::Vec4<Float>;


class Tracer {
 public:
  Tracer(int group, std::span<const UniformInput> uniform_inputs, FloatRules rules)
      : group_(static_cast<std::uint32_t>(group) << kGroupShift), uniform_inputs_(uniform_inputs), rules_(rules) {
    const Float zero = ZeroLane();
    for (auto& temp : temps_) temp.fill(zero);
  }

  void Trace(const Instruction& instruction) {
    if (rules_ == FloatRules::kLegacy) {
      TraceWith<FloatRules::kLegacy>(instruction);
    } else {
      TraceWith<FloatRules::kD3d9>(instruction);
    }
  }

  // A store of the output lane's final value, if the program wrote it.
  void StoreOutput(int slot, int c) {
    if (outputs_[slot][c].id != kNoArg) {
      jit::Trace(Op::kStore, outputs_[slot][c].id, kNoArg, kNoArg,
                 static_cast<std::uint32_t>(batch::OutputLane(slot, c)) | group_);
    }
  }

 // The machine interface of vm/core/operands.h: where the tracer keeps each register.
  using Float = jit::Float;
  using Vec4 = Vec4F;

  Vec4F ReadConstant(long index, bool relative) const {
    if (relative && address_written_) return Gather(index);
    Vec4F value = Zero();
    if (index < 0) return value;  // before any write a0 is 0
    for (int c = 0; c < 4; ++c) {
      value[c] = {jit::Trace(Op::kConstant, kNoArg, kNoArg, kNoArg, batch::ConstantIndex(static_cast<int>(index), c))};
    }
    return value;
  }

  Vec4F ReadInput(long index) const {
    Vec4F value;
    for (int c = 0; c < 4; ++c) {
      const auto uniform = std::ranges::find_if(uniform_inputs_, [&](const UniformInput& u) {
        return u.reg == index && u.component == c;
      });
      value[c] = uniform != uniform_inputs_.end()
                     ? Constant(Float{}, uniform->value)
                     : Float{jit::Trace(Op::kInput, kNoArg, kNoArg, kNoArg,
                                        static_cast<std::uint32_t>(batch::InputLane(static_cast<int>(index), c)) | group_)};
    }
    return value;
  }

  Vec4F& Temp(long index) { return temps_[static_cast<std::size_t>(index)]; }
  const Vec4F& Temp(long index) const { return temps_[static_cast<std::size_t>(index)]; }
  Vec4F& Output(int slot) { return outputs_[static_cast<std::size_t>(slot)]; }

  void WriteAddress(Float x) {
    address_ = semantics::AddressFromFloat(x);
    address_written_ = true;
  }

  static Vec4F Zero() {
    Vec4F zero;
    zero.fill(ZeroLane());
    return zero;
  }

 private:
  static Float ZeroLane() { return Constant(Float{}, 0.0f); }

  template <FloatRules kRules>
  void TraceWith(const Instruction& instruction) {
    switch (instruction.opcode) {
#define VS11_JIT_TRACE_CASE(name, ...) \
  case Opcode::k##name: semantics::Execute<semantics::name##Semantics, kRules>(*this, instruction); break;
      VS11_OPCODES(VS11_JIT_TRACE_CASE)
#undef VS11_JIT_TRACE_CASE
    }
  }

  // c[a0.x + index] of every vertex, component by component, by the rule the batch engine's
  // GatherKernel reads too (vm/core/constant_gather.h).
  Vec4F Gather(long index) const {
    const Int count = {jit::Trace(Op::kConstantCount)};
    const Int offset = semantics::RelativeConstantOffset(address_, static_cast<std::int32_t>(index), count,
                                                         batch::kFirstConstantRow, LiteralInt);
    Vec4F value;
    for (int c = 0; c < 4; ++c) {
      value[c] = {jit::Trace(Op::kGather, offset.id, kNoArg, kNoArg, static_cast<std::uint32_t>(c))};
    }
    return value;
  }

  std::array<Vec4F, kTempRegisterCount> temps_{};
  std::array<Vec4F, kOutputSlotCount> outputs_{};
  Int address_;
  bool address_written_ = false;
  std::uint32_t group_;
  std::span<const UniformInput> uniform_inputs_;
  FloatRules rules_;
};

}  // namespace

Graph TraceProgram(const Program& program, int groups, std::span<const UniformInput> uniform_inputs,
                   FloatRules rules) {
  Graph graph;
  tracing = &graph;
  std::vector<Tracer> tracers;
  for (int group = 0; group < groups; ++group) tracers.emplace_back(group, uniform_inputs, rules);
  for (const Instruction& instruction : program.instructions) {
    for (Tracer& tracer : tracers) tracer.Trace(instruction);
  }
  // Lane by lane, the groups' stores of a lane side by side: the groups' vectors are neighbours in
  // the lane's array, so two AVX2 groups fill one cache line at once, which a streaming store
  // (vmovntps) then writes whole. Group by group, 33 lanes apart, the write-combining buffers let
  // half-written lines go: all_instructions with AVX2 took twice as long streaming as caching (and
  // seven times batch's time on an Intel Xeon).
  for (int slot = 0; slot < kOutputSlotCount; ++slot) {
    for (int c = 0; c < 4; ++c) {
      for (Tracer& tracer : tracers) tracer.StoreOutput(slot, c);
    }
  }
  tracing = nullptr;
  return graph;
}

// Operations on the longest dependency chain.
int LongestChain(const Graph& graph) {
  std::vector<int> depth(graph.nodes().size(), 0);
  int longest = 0;
  for (std::size_t n = 0; n < graph.nodes().size(); ++n) {
    for (int arg : graph.nodes()[n].args) {
      if (arg != kNoArg) depth[n] = std::max(depth[n], depth[static_cast<std::size_t>(arg)] + 1);
    }
    longest = std::max(longest, depth[n]);
  }
  return longest;
}

}  // namespace vs11::jit
