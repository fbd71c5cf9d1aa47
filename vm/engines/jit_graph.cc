#include "vm/engines/jit_graph.h"

#include <algorithm>
#include <memory>
#include <vector>

#include "vm/core/constant_gather.h"
#include "vm/engines/batch_plan.h"
#include "vm/ir/lower_bits.h"
#include "vm/ir/record.h"

namespace vs11::jit {
namespace {

// Where one vertex group's registers live: the lane table's input lanes (or literals for uniform
// inputs) and the constant table.
class LoopBindings final : public ir::Bindings {
 public:
  LoopBindings(int group, std::span<const UniformInput> uniform_inputs)
      : group_(static_cast<std::uint32_t>(group) << kGroupShift), uniform_inputs_(uniform_inputs) {}

  ir::Vec4 ReadConstant(long index) override {
    ir::Vec4 value;
    for (int c = 0; c < 4; ++c) {
      value[c] = ir::RecordFloat(ir::Op::kConstant, {}, batch::ConstantIndex(static_cast<int>(index), c));
    }
    return value;
  }

  ir::Vec4 ReadInput(long index) override {
    ir::Vec4 value;
    for (int c = 0; c < 4; ++c) {
      const auto uniform = std::ranges::find_if(uniform_inputs_, [&](const UniformInput& u) {
        return u.reg == index && u.component == c;
      });
      value[c] = uniform != uniform_inputs_.end()
                     ? ir::Constant(ir::Float{}, uniform->value)
                     : ir::RecordFloat(ir::Op::kInput, {},
                                       static_cast<std::uint32_t>(batch::InputLane(static_cast<int>(index), c)) | group_);
    }
    return value;
  }

  std::uint32_t group() const { return group_; }

 private:
  std::uint32_t group_;
  std::span<const UniformInput> uniform_inputs_;
};

// The IR's relative reads as the batch engine's GatherKernel makes them too (vm/core/constant_gather.h):
// a kRelativeRow becomes the float offset of its row in the constant table, each kComponent of it a
// kGather of one float at that offset. Every other node is copied as it is, in order.
ir::Graph LowerRelativeRows(const ir::Graph& graph) {
  ir::Graph lowered;
  const ir::Recording recording(lowered);  // the offset's operations record into `lowered`
  std::vector<int> lowered_id(graph.size(), ir::kNoNode);
  for (std::size_t n = 0; n < graph.size(); ++n) {
    const ir::Node& node = graph.nodes()[n];
    ir::Args args = node.args;
    for (int& arg : args) {
      if (arg != ir::kNoNode) arg = lowered_id[static_cast<std::size_t>(arg)];
    }
    lowered.set_instruction(node.instruction);
    if (node.op == ir::Op::kRelativeRow) {
      const ir::Int count = ir::RecordInt(ir::Op::kConstantCount);
      lowered_id[n] = semantics::ConstantRowOffset(ir::Int{args[0]}, count, batch::kFirstConstantRow, ir::LiteralInt).id;
    } else if (node.op == ir::Op::kComponent) {
      lowered_id[n] = lowered.Add(ir::Op::kGather, {args[0]}, node.immediate);
    } else {
      lowered_id[n] = lowered.Add(node.op, node.type, {args[0], args[1], args[2]}, node.immediate);
    }
  }
  return lowered;
}

}  // namespace

ir::Graph RecordLoopBody(const Program& program, int groups, std::span<const UniformInput> uniform_inputs,
                         FloatRules rules) {
  ir::Graph graph;
  std::vector<std::unique_ptr<LoopBindings>> bindings;
  std::vector<ir::Bindings*> vertices;
  for (int group = 0; group < groups; ++group) {
    bindings.push_back(std::make_unique<LoopBindings>(group, uniform_inputs));
    vertices.push_back(bindings.back().get());
  }
  const std::vector<ir::RecordedOutputs> outputs = ir::RecordProgram(graph, program, vertices, rules);
  // Lane by lane, the groups' stores of a lane side by side: the groups' vectors are neighbours in
  // the lane's array, so two AVX2 groups fill one cache line at once, which a streaming store
  // (vmovntps) then writes whole. Group by group, 33 lanes apart, the write-combining buffers let
  // half-written lines go: all_instructions with AVX2 took twice as long streaming as caching (and
  // seven times batch's time on an Intel Xeon).
  for (int slot = 0; slot < kOutputSlotCount; ++slot) {
    for (int c = 0; c < 4; ++c) {
      for (int group = 0; group < groups; ++group) {
        const int value = outputs[static_cast<std::size_t>(group)].outputs[slot][c].id;
        if (value == ir::kNoNode) continue;  // a lane the program never writes
        graph.Add(ir::Op::kStore, {value},
                  static_cast<std::uint32_t>(batch::OutputLane(slot, c)) | bindings[static_cast<std::size_t>(group)]->group());
      }
    }
  }
  return ir::LowerToBitOperations(LowerRelativeRows(graph));
}

}  // namespace vs11::jit
