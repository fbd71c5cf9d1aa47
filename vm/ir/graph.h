// The IR every back end reads: a vs_1_1 program as a typed SSA graph of lane operations, recorded by
// running the instruction semantics (vm/core/semantics.h, vm/core/operands.h) over handle lane types
// (vm/ir/values.h; vm/ir/record.h drives them). The jit's x86 lowering (vm/engines/jit_*) and the
// GLSL/SPIR-V writer (vm/translate/) both start from it. vm/ir/README.md says what adding a primitive
// takes.
//
// A node is one operation on one lane of one vertex (a float, an int32, a mask) or, for a constant row
// read at a computed register number (c[a0.x + n]), a whole vec4, whose lanes kComponent reads: each back
// end lowers that pair its own way (the jit: a gather per lane at a float offset; GLSL: a row of the
// uniform array). Nodes are numbered in the order the semantics performed
// them, every argument before its users; identical pure nodes are made once (v0.x read by three dp4s
// is one node), which is all the common-subexpression elimination there is.
//
// Regions. vs_1_1 is straight-line code, so today every node is in region 0, the program body. Every
// node still names its region, and node sharing only reuses a node of the same region: when a later
// shader model brings loops, ifs, calls and predicated blocks, each becomes a region (its kind, its
// parent, the nodes that name it) appended to `regions`, the nodes stay one list in execution order
// with arguments first, and liveness, sharing and the back ends' in-order walks keep working. What a
// region adds is its own nodes and a back end's lowering of its kind, not a new graph.
#pragma once

#include <array>
#include <cstdint>
#include <cstddef>
#include <span>
#include <unordered_map>
#include <vector>

namespace vs11::ir {

enum class Type : std::uint8_t {
  kFloat,
  kInt,   // int32
  kMask,  // a bool per lane (a compare's result)
  kVec4,  // four floats (kRelativeRow), read by kComponent
};

// X(name, result type): the one list of operations. Arguments are node numbers; `immediate` carries
// what the operation names instead (a literal's bits, a shift count, a location a back end chose).
#define VS11_IR_OPS(X)                                                                                  \
  /* leaves */                                                                                          \
  X(Literal, kFloat)        /* immediate: the bits; type kFloat or kInt as recorded */                  \
  X(Input, kFloat)          /* immediate: an input lane as the back end numbers it */                   \
  X(Constant, kFloat)       /* immediate: a constant lane as the back end numbers it */                 \
  X(ConstantCount, kInt)    /* jit lowering only: the bank's size, known when the program runs */      \
  /* relative constant reads, c[a0.x + n]: a row by register number, then its lanes */                 \
  X(RelativeRow, kVec4)     /* arg: the register number (int); zeros outside the bank */                \
  X(Component, kFloat)      /* arg: a kVec4; immediate: the lane */                                     \
  X(Gather, kFloat)         /* jit lowering only: arg: a float offset into its table; immediate: lane */ \
  /* float arithmetic, IEEE single precision, unfused */                                                \
  X(Add, kFloat) X(Sub, kFloat) X(Mul, kFloat) X(Div, kFloat) X(Floor, kFloat) X(Sqrt, kFloat)          \
  X(Abs, kFloat)            /* the sign bit cleared, NaNs included */                                   \
  X(Negate, kFloat)         /* the sign bit flipped, NaNs included */                                   \
  /* compares: false where either side is NaN, but for Unordered (true where either is) */              \
  X(Less, kMask) X(Greater, kMask) X(GreaterEqual, kMask) X(Equal, kMask) X(Unordered, kMask)           \
  X(Select, kFloat)         /* args: mask, yes, no */                                                   \
  X(SelectZero, kInt)       /* args: mask, value: the value where the mask holds, else 0 */             \
  /* conversions: bit casts and int32 <-> float (truncating) */                                         \
  X(BitsOf, kInt) X(FloatFromBits, kFloat) X(ToInt, kInt) X(ToFloat, kFloat)                            \
  /* int32 arithmetic */                                                                                \
  X(IntAdd, kInt) X(IntSub, kInt) X(IntAnd, kInt) X(IntOr, kInt) X(IntXor, kInt)                        \
  X(ShiftLeft, kInt)        /* immediate: the count */                                                  \
  X(ShiftRight, kInt)       /* immediate: the count; arithmetic */                                      \
  X(IntGreater, kMask)      /* signed */                                                                \
  /* effects */                                                                                         \
  X(Store, kFloat)          /* arg: the value; immediate: an output lane as the back end numbers it */

enum class Op : std::uint8_t {
#define VS11_IR_OP_ENUM(name, type) k##name,
  VS11_IR_OPS(VS11_IR_OP_ENUM)
#undef VS11_IR_OP_ENUM
};

inline constexpr std::array kOpResultTypes = {
#define VS11_IR_OP_TYPE(name, type) Type::type,
    VS11_IR_OPS(VS11_IR_OP_TYPE)
#undef VS11_IR_OP_TYPE
};
inline constexpr int kOpCount = static_cast<int>(kOpResultTypes.size());
// The type an op's node has (a literal: as recorded).
constexpr Type ResultType(Op op) { return kOpResultTypes[static_cast<int>(op)]; }
const char* OpName(Op op);

inline constexpr int kNoNode = -1;
using Args = std::array<int, 3>;
// The arguments an operation is added with: those not given are kNoNode ({x} is x alone, {} none).
struct Operands {
  int a = kNoNode, b = kNoNode, c = kNoNode;
};

struct Node {
  Op op;
  Type type;
  Args args = {kNoNode, kNoNode, kNoNode};
  std::uint32_t immediate = 0;
  int instruction = -1;  // the program instruction whose semantics made it (-1: before the first)
  int region = 0;        // index into Graph::regions
};

enum class RegionKind : std::uint8_t { kBody };  // later: loop, if/else, call, predicated block
struct Region {
  RegionKind kind = RegionKind::kBody;
  int parent = -1;  // the enclosing region; -1 for the body
};

class Graph {
 public:
  // The node, or the existing identical one: pure nodes (all but stores) are shared within a region.
  int Add(Op op, Type type, Operands args = {}, std::uint32_t immediate = 0);
  int Add(Op op, Operands args = {}, std::uint32_t immediate = 0) { return Add(op, ResultType(op), args, immediate); }
  const std::vector<Node>& nodes() const { return nodes_; }
  const Node& operator[](int id) const { return nodes_[static_cast<std::size_t>(id)]; }
  std::size_t size() const { return nodes_.size(); }
  const std::vector<Region>& regions() const { return regions_; }
  // The instruction the next nodes belong to.
  void set_instruction(int index) { instruction_ = index; }

 private:
  std::vector<Node> nodes_;
  std::vector<Region> regions_ = {Region{}};
  // Sharing: the node of each (op, type, region, args, immediate), packed into one key.
  struct Key {
    std::uint64_t head;  // op, type, region, immediate
    Args args;
    bool operator==(const Key&) const = default;
  };
  struct KeyHash {
    std::size_t operator()(const Key& key) const;
  };
  std::unordered_map<Key, int, KeyHash> existing_;
  int instruction_ = -1;
  int region_ = 0;
};

// Which nodes matter and who reads them: stores and `roots` (a back end's final values), and
// everything they depend on; for each live node, the live nodes reading it, in order (a node that
// reads a value twice is listed twice).
struct Liveness {
  std::vector<bool> live;
  std::vector<std::vector<int>> users;
};
Liveness FindLiveness(const Graph& graph, std::span<const int> roots = {});

// Operations on the longest dependency chain.
int LongestChain(const Graph& graph);

}  // namespace vs11::ir
