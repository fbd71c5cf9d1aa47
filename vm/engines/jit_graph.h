// The jit's traced program: vm/core/semantics.h instantiated with a lane type that records operations
// instead of computing them, so that the graph holds the reference engine's IEEE operations in the
// reference engine's order. The emitters (vm/engines/jit_compiler.cc) turn it into machine code.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <span>
#include <tuple>
#include <vector>

#include "vm/core/program.h"
#include "vm/engines/jit_compiler.h"

namespace vs11::jit {

// ---- the traced program: a graph of vector operations on one vector of vertices ---------------------

enum class Op : std::uint8_t {
  kInput,     // immediate: lane table index
  kConstant,  // immediate: constant table index (broadcast)
  kLiteral,   // immediate: the float's bits (broadcast)
  kAdd, kSub, kMul, kDiv, kFloor, kSqrt,
  kLess, kGreater, kGreaterEqual, kEqual, kUnordered,  // masks (see IsMask)
  kSelect,      // args: mask, yes, no
  kSelectZero,  // args: mask, value: the value where the mask is true, else 0
  kMaskAnd,
  kIntAdd, kIntSub, kAnd, kOr, kXor, kShiftLeft, kShiftRight,  // immediate: shift count
  kToInt, kToFloat,
  kIntGreater,     // mask of a > b (signed)
  kConstantCount,  // RunArguments::constant_count (broadcast)
  kGather,         // args: constant table offset in floats; immediate: component (0..3)
  kStore,          // immediate: lane table index; args: value
};

constexpr int kNoArg = -1;

struct Node {
  Op op;
  std::array<int, 3> args = {kNoArg, kNoArg, kNoArg};
  std::uint32_t immediate = 0;
};

class Graph {
 public:
  // Identical pure nodes are made once (v0.x read by three dp4s is one load).
  int Add(Op op, std::array<int, 3> args = {kNoArg, kNoArg, kNoArg}, std::uint32_t immediate = 0) {
    if (op != Op::kStore) {
      const auto key = std::make_tuple(op, args, immediate);
      if (const auto it = existing_.find(key); it != existing_.end()) return it->second;
      existing_.emplace(key, static_cast<int>(nodes_.size()));
    }
    nodes_.push_back({op, args, immediate});
    return static_cast<int>(nodes_.size()) - 1;
  }
  const std::vector<Node>& nodes() const { return nodes_; }

 private:
  std::vector<Node> nodes_;
  std::map<std::tuple<Op, std::array<int, 3>, std::uint32_t>, int> existing_;
};


// Input and store nodes name a lane and, above kGroupShift, which of the loop's vertex groups
// (a vector of vertices each) they belong to.
constexpr int kGroupShift = 16;
constexpr std::uint32_t kLaneMask = (1u << kGroupShift) - 1;

// Masks are all-ones lanes where true in a vector register (AVX2), or bits of a mask register
// (AVX-512); every other value is a vector of floats or int32s.
constexpr bool IsMask(Op op) {
  return op == Op::kLess || op == Op::kGreater || op == Op::kGreaterEqual || op == Op::kEqual ||
         op == Op::kUnordered || op == Op::kIntGreater || op == Op::kMaskAnd;
}

// One vertex group per `groups`, interleaved instruction by instruction; `uniform_inputs` are
// compiled in as literals; products follow `rules`.
Graph TraceProgram(const Program& program, int groups, std::span<const UniformInput> uniform_inputs,
                   FloatRules rules);

// Operations on the longest dependency chain.
int LongestChain(const Graph& graph);

}  // namespace vs11::jit
