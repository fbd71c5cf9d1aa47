#include "vm/ir/lower_bits.h"

#include <vector>

namespace vs11::ir {

Graph LowerToBitOperations(const Graph& graph) {
  Graph lowered;
  std::vector<int> lowered_id(graph.size(), kNoNode);
  const auto literal = [&](std::uint32_t bits) { return lowered.Add(Op::kLiteral, Type::kInt, {}, bits); };
  for (std::size_t n = 0; n < graph.size(); ++n) {
    const Node& node = graph.nodes()[n];
    Args args = node.args;
    for (int& arg : args) {
      if (arg != kNoNode) arg = lowered_id[static_cast<std::size_t>(arg)];
    }
    lowered.set_instruction(node.instruction);
    switch (node.op) {
      case Op::kBitsOf: case Op::kFloatFromBits: lowered_id[n] = args[0]; break;
      case Op::kLiteral: lowered_id[n] = literal(node.immediate); break;
      case Op::kAbs: lowered_id[n] = lowered.Add(Op::kIntAnd, {args[0], literal(0x7FFFFFFFu)}); break;
      case Op::kNegate: lowered_id[n] = lowered.Add(Op::kIntXor, {args[0], literal(0x80000000u)}); break;
      default: lowered_id[n] = lowered.Add(node.op, node.type, {args[0], args[1], args[2]}, node.immediate); break;
    }
  }
  return lowered;
}

}  // namespace vs11::ir
