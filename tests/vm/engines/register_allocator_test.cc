// The jit's register allocator (vm/engines/register_allocator.h), apart from any encoding: free
// registers first, then the value used farthest in the future is evicted, a computed value is spilled
// once and a leaf never, pinned and hoisted values keep their registers, and a value's register is
// given up after its last use.
#include "vm/engines/register_allocator.h"

#include <gtest/gtest.h>

namespace vs11::jit {
namespace {

using ir::Op;

constexpr PinnedValues kNothingPinned = {ir::kNoNode, ir::kNoNode, ir::kNoNode};

// a (input), b = a + a, c = b * a, d = c - b, stored: b is read at c and d, a at b and c.
struct Chain {
  ir::Graph graph;
  int a, b, c, d;
  Chain() {
    a = graph.Add(Op::kInput, {}, 0);
    b = graph.Add(Op::kAdd, {a, a});
    c = graph.Add(Op::kMul, {b, a});
    d = graph.Add(Op::kSub, {c, b});
    graph.Add(Op::kStore, {d}, 0);
  }
};

TEST(RegisterAllocator, TakesFreeRegistersFirst) {
  Chain chain;
  RegisterAllocator allocator(chain.graph, 4);
  const RegisterAllocator::Taken first = allocator.TakeRegister(0, 4, chain.a, kNothingPinned, false);
  EXPECT_EQ(first.reg, 0);
  EXPECT_FALSE(first.spill);
  allocator.Assign(chain.a, first.reg);
  EXPECT_EQ(allocator.where(chain.a), 0);
  EXPECT_EQ(allocator.TakeRegister(0, 4, chain.b, kNothingPinned, false).reg, 1);
}

TEST(RegisterAllocator, EvictsTheValueUsedFarthestAndSpillsOnlyComputedValues) {
  Chain chain;
  RegisterAllocator allocator(chain.graph, 2);
  allocator.Assign(chain.a, 0);  // next read at c
  allocator.Assign(chain.b, 1);  // next read at c, then d
  // At c, a is never read again and b is read at d: a goes, without a spill (an input is reloaded).
  const RegisterAllocator::Taken for_c = allocator.TakeRegister(0, 2, chain.c, kNothingPinned, false);
  EXPECT_EQ(for_c.reg, 0);
  EXPECT_FALSE(for_c.spill);
  EXPECT_EQ(allocator.where(chain.a), ir::kNoNode);
  allocator.Assign(chain.c, for_c.reg);
  // Past d nothing is read: with c pinned, b (a computed value) is evicted and spilled, once.
  const PinnedValues c_pinned = {chain.c, ir::kNoNode, ir::kNoNode};
  const RegisterAllocator::Taken for_d = allocator.TakeRegister(0, 2, chain.d, c_pinned, true);
  EXPECT_EQ(for_d.reg, 1);
  ASSERT_TRUE(for_d.spill);
  EXPECT_EQ(*for_d.spill, chain.b);
  EXPECT_EQ(allocator.spill_slot(chain.b), 0);
  EXPECT_EQ(allocator.spilled_values(), 1);
  EXPECT_EQ(allocator.spilled_masks(), 1);
  EXPECT_EQ(allocator.spill_slots(), 1);
}

TEST(RegisterAllocator, GivesARegisterUpAfterTheLastUseButNotAHoistedOne) {
  Chain chain;
  RegisterAllocator allocator(chain.graph, 4);
  allocator.Assign(chain.a, 0);
  allocator.Assign(chain.b, 1);
  allocator.ReleaseAfterLastUse(chain.a, chain.b);  // a is read again at c
  EXPECT_EQ(allocator.where(chain.a), 0);
  allocator.ReleaseAfterLastUse(chain.a, chain.c);
  EXPECT_EQ(allocator.where(chain.a), ir::kNoNode);
  allocator.Hoist(chain.b);
  allocator.ReleaseAfterLastUse(chain.b, chain.d);
  EXPECT_EQ(allocator.where(chain.b), 1);
  EXPECT_EQ(allocator.NextUse(chain.b, chain.b), chain.c);
  EXPECT_EQ(allocator.NextUse(chain.b, chain.d), RegisterAllocator::kNever);
}

}  // namespace
}  // namespace vs11::jit
