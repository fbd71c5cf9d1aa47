#include "vm/ir/graph.h"

#include <algorithm>

namespace vs11::ir {

const char* OpName(Op op) {
  switch (op) {
#define VS11_IR_OP_NAME(name, type) \
  case Op::k##name: return #name;
    VS11_IR_OPS(VS11_IR_OP_NAME)
#undef VS11_IR_OP_NAME
  }
  return "?";
}

int Graph::Add(Op op, Type type, Operands operands, std::uint32_t immediate) {
  const Args args = {operands.a, operands.b, operands.c};
  if (op != Op::kStore) {
    const auto key = std::make_tuple(op, type, region_, args, immediate);
    if (const auto it = existing_.find(key); it != existing_.end()) return it->second;
    existing_.emplace(key, static_cast<int>(nodes_.size()));
  }
  nodes_.push_back({op, type, args, immediate, instruction_, region_});
  return static_cast<int>(nodes_.size()) - 1;
}

Liveness FindLiveness(const Graph& graph, std::span<const int> roots) {
  const std::vector<Node>& nodes = graph.nodes();
  Liveness result;
  result.live.assign(nodes.size(), false);
  result.users.assign(nodes.size(), {});
  for (int root : roots) {
    if (root != kNoNode) result.live[static_cast<std::size_t>(root)] = true;
  }
  // Arguments always come before their users: one backward pass suffices.
  for (std::size_t n = nodes.size(); n-- > 0;) {
    if (nodes[n].op == Op::kStore) result.live[n] = true;
    if (!result.live[n]) continue;
    for (int arg : nodes[n].args) {
      if (arg != kNoNode) result.live[static_cast<std::size_t>(arg)] = true;
    }
  }
  for (std::size_t n = 0; n < nodes.size(); ++n) {
    if (!result.live[n]) continue;
    for (int arg : nodes[n].args) {
      if (arg != kNoNode) result.users[static_cast<std::size_t>(arg)].push_back(static_cast<int>(n));
    }
  }
  return result;
}

int LongestChain(const Graph& graph) {
  std::vector<int> depth(graph.size(), 0);
  int longest = 0;
  for (std::size_t n = 0; n < graph.size(); ++n) {
    for (int arg : graph.nodes()[n].args) {
      if (arg != kNoNode) depth[n] = std::max(depth[n], depth[static_cast<std::size_t>(arg)] + 1);
    }
    longest = std::max(longest, depth[n]);
  }
  return longest;
}

}  // namespace vs11::ir
