// Recording a program into the IR (vm/ir/record.h): every opcode reaches its semantics through the one
// dispatch, the bindings decide where registers come from, and several vertices interleave.
#include "vm/ir/record.h"

#include <algorithm>
#include <string>

#include <gtest/gtest.h>

#include "tests/vm/engines/random_program.h"

namespace vs11::ir {
namespace {

using random_program::Const;
using random_program::Input;
using random_program::MakeInstruction;
using random_program::Output;
using random_program::Src;

// Inputs and constants as register * 4 + lane (inputs plus the vertex's tag).
class TestBindings final : public Bindings {
 public:
  explicit TestBindings(std::uint32_t tag = 0) : tag_(tag) {}
  Vec4 ReadConstant(long index) override { return Lanes(Op::kConstant, index, 0); }
  Vec4 ReadInput(long index) override { return Lanes(Op::kInput, index, tag_); }

 private:
  static Vec4 Lanes(Op op, long index, std::uint32_t tag) {
    Vec4 value;
    for (int c = 0; c < 4; ++c) value[c] = RecordFloat(op, {}, tag + static_cast<std::uint32_t>(index * 4 + c));
    return value;
  }
  std::uint32_t tag_;
};

bool DependsOn(const Graph& graph, int node, Op leaf) {
  if (node == kNoNode) return false;
  if (graph[node].op == leaf) return true;
  return std::ranges::any_of(graph[node].args, [&](int arg) { return DependsOn(graph, arg, leaf); });
}

// One instruction of every opcode writing oD0 from v0 (and c0.. for the second source, the matrix):
// every opcode with a result computes each lane it writes from its source, nop, dcl and def record
// nothing but the zero every register starts at.
TEST(IrRecord, EveryOpcodeReachesItsSemanticsThroughTheDispatch) {
  const int slot = static_cast<int>(OutputSlot::kDiffuse);
  for (const OpcodeInfo& info : kOpcodeTable) {
    if (info.since != ShaderModel::kVs11) continue;  // the machine the engines run
    Program program;
    const WriteMask mask = random_program::LegalMasks(info).back();
    program.instructions.push_back(MakeInstruction(info.opcode, {Output(slot), mask},
                                                   {Src(Input(0)), Src(Const(0)), Src(Input(1))}));
    Graph graph;
    TestBindings bindings;
    Bindings* const vertices[] = {&bindings};
    const RecordedOutputs outputs = RecordProgram(graph, program, vertices, FloatRules::kD3d9).at(0);
    if (info.kind == ResultKind::kNoResult) {
      EXPECT_EQ(graph.size(), 1u) << info.mnemonic;  // the literal 0 the temporaries start at
      continue;
    }
    for (int lane = 0; lane < info.result_lanes(); ++lane) {
      const int value = outputs.outputs[slot][lane].id;
      if (!mask.has(lane)) {
        EXPECT_EQ(value, kNoNode) << info.mnemonic << " lane " << lane;
        continue;
      }
      ASSERT_NE(value, kNoNode) << info.mnemonic << " lane " << lane;
      // lit's x and w, dst's x and expp's and logp's w are the constant 1, dst's w is c0.w; every
      // other lane reads v0.
      const bool constant_lane = (info.opcode == Opcode::kLit && (lane == 0 || lane == 3)) ||
                                 (info.opcode == Opcode::kDst && (lane == 0 || lane == 3)) ||
                                 ((info.opcode == Opcode::kExpp || info.opcode == Opcode::kLogp) && lane == 3);
      EXPECT_EQ(DependsOn(graph, value, Op::kInput), !constant_lane) << info.mnemonic << " lane " << lane;
      if (!constant_lane) {
        EXPECT_EQ(graph[value].instruction, 0) << info.mnemonic;
      }
    }
    if (info.kind == ResultKind::kMatrix || info.opcode == Opcode::kDst) {
      EXPECT_TRUE(DependsOn(graph, outputs.outputs[slot][1].id, Op::kConstant)) << info.mnemonic;
    }
  }
}

// c[a0.x + 3] is one kRelativeRow of the register number a0.x + 3, whatever the bindings (the back
// ends lower it), read lane by lane; before a0 is written it is the static c3.
TEST(IrRecord, RelativeReadsAreOneRowByRegisterNumberOnceA0IsWritten) {
  Program program;
  const int slot = static_cast<int>(OutputSlot::kDiffuse);
  program.instructions.push_back(MakeInstruction(Opcode::kMov, {Output(slot), WriteMask(0x1)}, {Src(Const(3, true))}));
  program.instructions.push_back(
      MakeInstruction(Opcode::kMov, {random_program::kAddressRegister, WriteMask(0x1)}, {Src(Input(0))}));
  program.instructions.push_back(MakeInstruction(Opcode::kMov, {Output(slot), WriteMask(0x2)}, {Src(Const(3, true))}));
  Graph graph;
  TestBindings bindings;
  Bindings* const vertices[] = {&bindings};
  const RecordedOutputs outputs = RecordProgram(graph, program, vertices, FloatRules::kD3d9).at(0);
  EXPECT_EQ(graph[outputs.outputs[slot][0].id].op, Op::kConstant);  // a0 is 0 before the mov
  EXPECT_EQ(graph[outputs.outputs[slot][0].id].immediate, 12u);
  const Node& lane = graph[outputs.outputs[slot][1].id];
  EXPECT_EQ(lane.op, Op::kComponent);
  EXPECT_EQ(lane.immediate, 1u);
  const Node& row = graph[lane.args[0]];
  ASSERT_EQ(row.op, Op::kRelativeRow);
  EXPECT_EQ(row.type, Type::kVec4);
  const Node& register_number = graph[row.args[0]];
  ASSERT_EQ(register_number.op, Op::kIntAdd);
  EXPECT_EQ(graph[register_number.args[1]].op, Op::kLiteral);
  EXPECT_EQ(graph[register_number.args[1]].immediate, 3u);
  EXPECT_TRUE(DependsOn(graph, register_number.args[0], Op::kInput));
}

TEST(IrRecord, VerticesInterleaveInstructionByInstructionAndShareWhatTheyShare) {
  Program program;
  const int slot = static_cast<int>(OutputSlot::kDiffuse);
  program.instructions.push_back(MakeInstruction(Opcode::kAdd, {Output(slot), WriteMask(0x1)}, {Src(Input(0)), Src(Const(0))}));
  program.instructions.push_back(MakeInstruction(Opcode::kMul, {Output(slot), WriteMask(0x2)}, {Src(Input(0)), Src(Const(0))}));
  Graph graph;
  TestBindings first(0), second(1000);
  Bindings* const vertices[] = {&first, &second};
  const std::vector<RecordedOutputs> outputs = RecordProgram(graph, program, vertices, FloatRules::kD3d9);
  ASSERT_EQ(outputs.size(), 2u);
  // Both adds (instruction 0) come before both multiplies, and each vertex reads its own inputs but
  // the one constant node.
  EXPECT_LT(outputs[1].outputs[slot][0].id, outputs[0].outputs[slot][1].id);
  EXPECT_NE(outputs[0].outputs[slot][0].id, outputs[1].outputs[slot][0].id);
  EXPECT_EQ(graph[outputs[0].outputs[slot][0].id].args[1], graph[outputs[1].outputs[slot][0].id].args[1]);
}

TEST(IrRecord, TheLegacyRuleRecordsSelectsAroundEachProduct) {
  Program program;
  const int slot = static_cast<int>(OutputSlot::kDiffuse);
  program.instructions.push_back(MakeInstruction(Opcode::kMul, {Output(slot), WriteMask(0x1)}, {Src(Input(0)), Src(Const(0))}));
  for (const FloatRules rules : {FloatRules::kD3d9, FloatRules::kLegacy}) {
    Graph graph;
    TestBindings bindings;
    Bindings* const vertices[] = {&bindings};
    const int product = RecordProgram(graph, program, vertices, rules).at(0).outputs[slot][0].id;
    ASSERT_EQ(graph[product].op, Op::kMul);
    EXPECT_EQ(graph[graph[product].args[0]].op, rules == FloatRules::kLegacy ? Op::kSelect : Op::kInput);
  }
}

}  // namespace
}  // namespace vs11::ir
