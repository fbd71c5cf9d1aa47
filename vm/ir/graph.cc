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
    const Key key = {static_cast<std::uint64_t>(op) | static_cast<std::uint64_t>(type) << 8 |
                         static_cast<std::uint64_t>(static_cast<std::uint16_t>(region_)) << 16 |
                         static_cast<std::uint64_t>(immediate) << 32,
                     args};
    const auto [it, added] = existing_.try_emplace(key, static_cast<int>(nodes_.size()));
    if (!added) return it->second;
  }
  nodes_.push_back({op, type, args, immediate, instruction_, region_});
  return static_cast<int>(nodes_.size()) - 1;
}

std::size_t Graph::KeyHash::operator()(const Key& key) const {
  std::uint64_t hash = key.head * 0x9E3779B97F4A7C15u;
  for (int arg : key.args) hash = (hash ^ static_cast<std::uint32_t>(arg)) * 0x100000001B3u;
  return static_cast<std::size_t>(hash ^ (hash >> 29));
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
