// The jit's register allocator, apart from any instruction set's encodings (vm/engines/jit_compiler.cc
// encodes AVX2 and AVX-512 around it; another ISA would reuse it as it is). It walks an ir::Graph in
// node order and keeps which register holds which value, which values are spilled to which slot of
// the spill buffer, and which constants are hoisted into registers for the whole loop. When every
// register of a kind is taken it evicts the value used farthest in the future (Belady's choice) and
// says which value the encoder must store first; it emits nothing itself.
#pragma once

#include <algorithm>
#include <array>
#include <cassert>
#include <limits>
#include <optional>
#include <vector>

#include "vm/ir/graph.h"

namespace vs11::jit {

// Leaves read straight from where they live (a lane, the constant table, the literal pool, the
// arguments): evicted without a spill, loaded again where they are used.
constexpr bool Rematerializable(ir::Op op) {
  return op == ir::Op::kInput || op == ir::Op::kConstant || op == ir::Op::kLiteral || op == ir::Op::kConstantCount;
}

// An operation's operands stay in their registers while its other operands and its result are
// placed: the allocator never evicts these.
using PinnedValues = std::array<int, 3>;

class RegisterAllocator {
 public:
  static constexpr int kNever = std::numeric_limits<int>::max();

  // `register_count`: register numbers [0, register_count) of every kind the encoder numbers.
  RegisterAllocator(const ir::Graph& graph, int register_count)
      : nodes_(graph.nodes()), register_value_(static_cast<std::size_t>(register_count), ir::kNoNode),
        spill_slot_(graph.size(), -1), where_(graph.size(), ir::kNoNode) {
    ir::Liveness liveness = ir::FindLiveness(graph);
    live_ = std::move(liveness.live);
    users_ = std::move(liveness.users);
  }

  bool live(int value) const { return live_[static_cast<std::size_t>(value)]; }
  const std::vector<int>& users(int value) const { return users_[static_cast<std::size_t>(value)]; }
  // The register holding `value`, or ir::kNoNode.
  int where(int value) const { return where_[static_cast<std::size_t>(value)]; }
  // The spill slot of `value`, or -1.
  int spill_slot(int value) const { return spill_slot_[static_cast<std::size_t>(value)]; }
  int spill_slots() const { return spill_slots_; }
  int spilled_values() const { return spilled_values_; }
  int spilled_masks() const { return spilled_masks_; }

  // The position of the next use of `value` after `position`, or kNever.
  int NextUse(int value, int position) const {
    const std::vector<int>& uses = users(value);
    const auto it = std::upper_bound(uses.begin(), uses.end(), position);
    return it == uses.end() ? kNever : *it;
  }

  // A value kept in its register for the whole loop.
  void Hoist(int value) { hoisted_.push_back(value); }
  bool Hoisted(int value) const { return std::find(hoisted_.begin(), hoisted_.end(), value) != hoisted_.end(); }

  // A slot of the spill buffer given to `value` for good (the encoder fills it).
  int NewSpillSlot(int value) { return spill_slot_[static_cast<std::size_t>(value)] = spill_slots_++; }

  void Assign(int value, int reg) {
    where_[static_cast<std::size_t>(value)] = reg;
    register_value_[static_cast<std::size_t>(reg)] = value;
  }
  void Release(int value) {
    register_value_[static_cast<std::size_t>(where(value))] = ir::kNoNode;
    where_[static_cast<std::size_t>(value)] = ir::kNoNode;
  }
  // Gives up `value`'s register after its last use at `position` (hoisted values keep theirs).
  void ReleaseAfterLastUse(int value, int position) {
    if (value != ir::kNoNode && where(value) != ir::kNoNode && !Hoisted(value) && NextUse(value, position) == kNever) {
      Release(value);
    }
  }

  // What TakeRegister decided: the register, and the value the encoder must store to its new spill
  // slot first, if the evicted one needs one.
  struct Taken {
    int reg;
    std::optional<int> spill;
  };

  // A free register among [first, end) for the operation at `position`, evicting the value used
  // farthest in the future (not one of `pinned`). A pinned value holds one register at most, and the
  // encoder gives each kind more registers than there are pinned values, so one can be evicted.
  // `mask`: the range is mask registers (counted apart in spilled_masks()).
  Taken TakeRegister(int first, int end, int position, const PinnedValues& pinned, bool mask) {
    for (int reg = first; reg < end; ++reg) {
      if (register_value_[static_cast<std::size_t>(reg)] == ir::kNoNode) return {reg, std::nullopt};
    }
    int victim = -1, farthest = -1;
    for (int reg = first; reg < end; ++reg) {
      const int held = register_value_[static_cast<std::size_t>(reg)];
      if (std::find(pinned.begin(), pinned.end(), held) != pinned.end()) continue;
      const int next = NextUse(held, position);
      if (next > farthest) farthest = next, victim = reg;
    }
    assert(victim >= 0 && "every register holds a pinned value");
    const int held = register_value_[static_cast<std::size_t>(victim)];
    std::optional<int> spill;
    if (!Rematerializable(nodes_[static_cast<std::size_t>(held)].op) && spill_slot(held) < 0) {
      NewSpillSlot(held);
      ++spilled_values_;
      spilled_masks_ += mask ? 1 : 0;
      spill = held;
    }
    Release(held);
    return {victim, spill};
  }

 private:
  const std::vector<ir::Node>& nodes_;
  std::vector<bool> live_;
  std::vector<std::vector<int>> users_;
  std::vector<int> register_value_;  // value in each register, by number
  std::vector<int> spill_slot_;
  std::vector<int> where_;           // register of each value
  std::vector<int> hoisted_;
  int spill_slots_ = 0;
  int spilled_values_ = 0;
  int spilled_masks_ = 0;
};

}  // namespace vs11::jit
