// The IR's graph (vm/ir/graph.h): node sharing, liveness, the longest chain, and the x86 lowering
// (vm/ir/lower_bits.h).
#include "vm/ir/graph.h"

#include <gtest/gtest.h>

#include "vm/ir/lower_bits.h"

namespace vs11::ir {
namespace {

TEST(IrGraph, AddMakesIdenticalPureNodesOnceButEveryStore) {
  Graph graph;
  const int x = graph.Add(Op::kInput, {}, 7);
  EXPECT_EQ(graph.Add(Op::kInput, {}, 7), x);
  EXPECT_NE(graph.Add(Op::kInput, {}, 8), x);
  const int sum = graph.Add(Op::kAdd, {x, x, kNoNode});
  EXPECT_EQ(graph.Add(Op::kAdd, {x, x, kNoNode}), sum);
  EXPECT_NE(graph.Add(Op::kMul, {x, x, kNoNode}), sum);
  const int store = graph.Add(Op::kStore, {sum, kNoNode, kNoNode}, 3);
  EXPECT_NE(graph.Add(Op::kStore, {sum, kNoNode, kNoNode}, 3), store);
  EXPECT_EQ(graph.size(), 6u);
}

TEST(IrGraph, LiteralsOfOneBitPatternAreSharedOnlyWithinTheirType) {
  Graph graph;
  const int float_zero = graph.Add(Op::kLiteral, Type::kFloat, {}, 0);
  const int int_zero = graph.Add(Op::kLiteral, Type::kInt, {}, 0);
  EXPECT_NE(float_zero, int_zero);
  EXPECT_EQ(graph.Add(Op::kLiteral, Type::kInt, {}, 0), int_zero);
  EXPECT_EQ(graph[int_zero].type, Type::kInt);
}

TEST(IrGraph, NodesRememberTheirInstructionAndRegion) {
  Graph graph;
  const int before = graph.Add(Op::kInput, {}, 0);
  graph.set_instruction(4);
  const int during = graph.Add(Op::kInput, {}, 1);
  EXPECT_EQ(graph[before].instruction, -1);
  EXPECT_EQ(graph[during].instruction, 4);
  EXPECT_EQ(graph[during].region, 0);
  ASSERT_EQ(graph.regions().size(), 1u);
  EXPECT_EQ(graph.regions()[0].kind, RegionKind::kBody);
}

TEST(IrGraph, LivenessFollowsStoresAndRootsAndListsEveryRead) {
  Graph graph;
  const int a = graph.Add(Op::kInput, {}, 0);
  const int b = graph.Add(Op::kInput, {}, 1);
  const int dead = graph.Add(Op::kSqrt, {b});
  const int square = graph.Add(Op::kMul, {a, a});
  const int root = graph.Add(Op::kFloor, {b});
  const int store = graph.Add(Op::kStore, {square}, 0);
  const Liveness stores_only = FindLiveness(graph);
  EXPECT_TRUE(stores_only.live[a]);
  EXPECT_TRUE(stores_only.live[square]);
  EXPECT_TRUE(stores_only.live[store]);
  EXPECT_FALSE(stores_only.live[b]);
  EXPECT_FALSE(stores_only.live[dead]);
  EXPECT_FALSE(stores_only.live[root]);
  EXPECT_EQ(stores_only.users[a], (std::vector<int>{square, square}));  // read twice, listed twice
  EXPECT_TRUE(stores_only.users[b].empty());                             // its readers are dead

  const int roots[] = {root};
  const Liveness with_root = FindLiveness(graph, roots);
  EXPECT_TRUE(with_root.live[b]);
  EXPECT_TRUE(with_root.live[root]);
  EXPECT_FALSE(with_root.live[dead]);
  EXPECT_EQ(with_root.users[b], (std::vector<int>{root}));
}

TEST(IrGraph, LongestChainCountsTheDeepestPath) {
  Graph graph;
  const int a = graph.Add(Op::kInput, {}, 0);
  const int b = graph.Add(Op::kInput, {}, 1);
  EXPECT_EQ(LongestChain(graph), 0);
  int chain = graph.Add(Op::kAdd, {a, b, kNoNode});
  for (int k = 0; k < 4; ++k) chain = graph.Add(Op::kMul, {chain, a, kNoNode});
  const int side = graph.Add(Op::kSub, {a, b, kNoNode});
  graph.Add(Op::kSelect, {graph.Add(Op::kLess, {side, b, kNoNode}), chain, side});
  EXPECT_EQ(LongestChain(graph), 6);  // add, four muls, select
}

TEST(IrGraph, EveryOpHasANameAndItsResultType) {
  for (int op = 0; op < kOpCount; ++op) EXPECT_STRNE(OpName(static_cast<Op>(op)), "?") << op;
  EXPECT_EQ(ResultType(Op::kLess), Type::kMask);
  EXPECT_EQ(ResultType(Op::kRelativeRow), Type::kVec4);
  EXPECT_EQ(ResultType(Op::kToInt), Type::kInt);
}

TEST(IrLowerToBitOperations, BitCastsVanishAbsAndNegateBecomeBitOperations) {
  Graph graph;
  const int x = graph.Add(Op::kInput, {}, 0);
  const int abs = graph.Add(Op::kAbs, {x});
  const int neg = graph.Add(Op::kNegate, {abs});
  const int bits = graph.Add(Op::kBitsOf, {neg});
  const int shifted = graph.Add(Op::kShiftRight, {bits}, 23);
  graph.Add(Op::kStore, {graph.Add(Op::kFloatFromBits, {shifted})}, 0);
  const Graph lowered = LowerToBitOperations(graph);
  // input, 0x7FFFFFFF, and, 0x80000000, xor, shift, store
  ASSERT_EQ(lowered.size(), 7u);
  EXPECT_EQ(lowered[1].op, Op::kLiteral);
  EXPECT_EQ(lowered[1].immediate, 0x7FFFFFFFu);
  EXPECT_EQ(lowered[2].op, Op::kIntAnd);
  EXPECT_EQ(lowered[2].args[0], 0);
  EXPECT_EQ(lowered[2].args[1], 1);
  EXPECT_EQ(lowered[3].immediate, 0x80000000u);
  EXPECT_EQ(lowered[4].op, Op::kIntXor);
  EXPECT_EQ(lowered[4].args[0], 2);
  EXPECT_EQ(lowered[5].op, Op::kShiftRight);
  EXPECT_EQ(lowered[5].args[0], 4);  // the xor itself: BitsOf is gone
  EXPECT_EQ(lowered[6].op, Op::kStore);
  EXPECT_EQ(lowered[6].args[0], 5);  // and FloatFromBits too
}

TEST(IrLowerToBitOperations, LiteralsOfOneBitPatternBecomeOne) {
  Graph graph;
  const int float_zero = graph.Add(Op::kLiteral, Type::kFloat, {}, 0);
  const int int_zero = graph.Add(Op::kLiteral, Type::kInt, {}, 0);
  graph.Add(Op::kStore, {float_zero}, 0);
  graph.Add(Op::kStore, {int_zero}, 1);
  const Graph lowered = LowerToBitOperations(graph);
  ASSERT_EQ(lowered.size(), 3u);
  EXPECT_EQ(lowered[1].args[0], 0);
  EXPECT_EQ(lowered[2].args[0], 0);
}

}  // namespace
}  // namespace vs11::ir
