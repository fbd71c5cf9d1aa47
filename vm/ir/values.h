// The lane types vm/core/semantics.h and vm/core/operands.h are instantiated with to record a graph
// (vm/ir/graph.h): handles to nodes, typed so that float, integer and mask operations resolve as they
// do for float/int32/bool and Highway vectors. Each operation adds its node to the graph that a
// Recording names (one at a time per thread: the semantics' free functions take no graph argument).
#pragma once

#include <bit>
#include <cstdint>

#include "vm/core/semantics.h"
#include "vm/ir/graph.h"

namespace vs11::ir {

// Sets the graph this thread's handles record into, for its lifetime.
class Recording {
 public:
  explicit Recording(Graph& graph);
  ~Recording();
  Recording(const Recording&) = delete;
  Recording& operator=(const Recording&) = delete;
  static Graph& graph();
};

int Record(Op op, Type type, Operands args = {}, std::uint32_t immediate = 0);

struct Float {
  int id = kNoNode;
};
struct Int {
  int id = kNoNode;
};
struct Mask {
  int id = kNoNode;
};

inline Float RecordFloat(Op op, Operands args = {}, std::uint32_t immediate = 0) {
  return {Record(op, Type::kFloat, args, immediate)};
}
inline Int RecordInt(Op op, Operands args = {}, std::uint32_t immediate = 0) {
  return {Record(op, Type::kInt, args, immediate)};
}
inline Mask RecordMask(Op op, int a, int b) { return {Record(op, Type::kMask, {a, b})}; }

inline Float operator+(Float a, Float b) { return RecordFloat(Op::kAdd, {a.id, b.id}); }
inline Float operator-(Float a, Float b) { return RecordFloat(Op::kSub, {a.id, b.id}); }
inline Float operator*(Float a, Float b) { return RecordFloat(Op::kMul, {a.id, b.id}); }
inline Float operator/(Float a, Float b) { return RecordFloat(Op::kDiv, {a.id, b.id}); }
inline Mask operator<(Float a, Float b) { return RecordMask(Op::kLess, a.id, b.id); }
inline Mask operator>(Float a, Float b) { return RecordMask(Op::kGreater, a.id, b.id); }
inline Mask operator>=(Float a, Float b) { return RecordMask(Op::kGreaterEqual, a.id, b.id); }
inline Mask operator==(Float a, Float b) { return RecordMask(Op::kEqual, a.id, b.id); }
inline Mask operator>(Int a, Int b) { return RecordMask(Op::kIntGreater, a.id, b.id); }
inline Int operator+(Int a, Int b) { return RecordInt(Op::kIntAdd, {a.id, b.id}); }
inline Int operator-(Int a, Int b) { return RecordInt(Op::kIntSub, {a.id, b.id}); }
inline Int operator&(Int a, Int b) { return RecordInt(Op::kIntAnd, {a.id, b.id}); }
inline Int operator|(Int a, Int b) { return RecordInt(Op::kIntOr, {a.id, b.id}); }

inline Float LiteralBits(std::uint32_t bits) { return RecordFloat(Op::kLiteral, {}, bits); }
inline Int LiteralInt(std::int32_t value) { return RecordInt(Op::kLiteral, {}, static_cast<std::uint32_t>(value)); }
inline Float Constant(Float, float value) { return LiteralBits(std::bit_cast<std::uint32_t>(value)); }
inline Int ConstantInt(Float, std::int32_t value) { return LiteralInt(value); }
inline Int BitsOf(Float x) { return RecordInt(Op::kBitsOf, {x.id}); }
inline Float FloatFromBits(Int x) { return RecordFloat(Op::kFloatFromBits, {x.id}); }
inline Float Floor(Float x) { return RecordFloat(Op::kFloor, {x.id}); }
inline Float Sqrt(Float x) { return RecordFloat(Op::kSqrt, {x.id}); }
inline Float Abs(Float x) { return RecordFloat(Op::kAbs, {x.id}); }
inline Float Negate(Float x) { return RecordFloat(Op::kNegate, {x.id}); }
inline Mask IsNaN(Float x) { return RecordMask(Op::kUnordered, x.id, x.id); }
inline Float IfThenElse(Mask condition, Float yes, Float no) {
  return RecordFloat(Op::kSelect, {condition.id, yes.id, no.id});
}
inline Int IfThenElseZero(Mask condition, Int value) { return RecordInt(Op::kSelectZero, {condition.id, value.id}); }
inline Int ToInt(Float x) { return RecordInt(Op::kToInt, {x.id}); }
inline Float ToFloat(Int x) { return RecordFloat(Op::kToFloat, {x.id}); }
template <int kBits>
Int ShiftLeft(Int x) {
  return RecordInt(Op::kShiftLeft, {x.id}, kBits);
}
template <int kBits>
Int ShiftRight(Int x) {
  return RecordInt(Op::kShiftRight, {x.id}, kBits);
}

using Vec4 = semantics::Vec4<Float>;

}  // namespace vs11::ir
