// The jit's recorded program (vm/engines/jit_graph.cc), apart from the machine code made from it: the
// graph, evaluated node by node with one C++ operation per node as the emitter's instruction performs
// it, computes what the reference engine computes, bit for bit, on random programs, with two vertex
// groups recorded side by side; identical loads are one node, uniform inputs are literals, relative
// reads gather only after a0 is written, and every output lane the program writes is stored once
// per group, the groups' stores of a lane side by side.
#include "vm/engines/jit_graph.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/vm/engines/random_program.h"
#include "vm/asm/assembler.h"
#include "vm/asm/disassembler.h"
#include "vm/engines/batch_plan.h"
#include "vm/engines/reference_engine.h"

namespace vs11::jit {
namespace {

using ir::Graph;
using ir::Node;
using ir::Op;

using random_program::Bits;

// ---- the graph, evaluated for one vertex per group ---------------------------------------------------

struct Value {
  std::uint32_t bits = 0;  // a float's or an int32's bits (BitsOf and FloatFromBits share a node)
  bool mask = false;
};

float F(const Value& v) { return std::bit_cast<float>(v.bits); }
std::int32_t I(const Value& v) { return std::bit_cast<std::int32_t>(v.bits); }
Value OfFloat(float f) { return {std::bit_cast<std::uint32_t>(f)}; }
Value OfInt(std::int32_t i) { return {std::bit_cast<std::uint32_t>(i)}; }
Value OfMask(bool m) { return {0, m}; }

// vcvttps2dq: truncation, and the "integer indefinite" INT32_MIN for NaN and out-of-range values.
std::int32_t ConvertTruncating(float x) {
  if (!(x >= -2147483648.0f && x < 2147483648.0f)) return std::numeric_limits<std::int32_t>::min();
  return static_cast<std::int32_t>(x);
}

// What one vertex group reads: its inputs by lane index, and the constant table (batch_plan.h rows).
struct GroupData {
  std::map<int, float> inputs;
};

struct Evaluation {
  std::map<std::uint32_t, float> stores;  // by store immediate (lane | group << kGroupShift)
  std::string error;
};

Value EvaluateArithmetic(const Node& node, const std::vector<Value>& values) {
  auto a = [&](int k) { return values[static_cast<std::size_t>(node.args[static_cast<std::size_t>(k)])]; };
  switch (node.op) {
    case Op::kAdd: return OfFloat(F(a(0)) + F(a(1)));
    case Op::kSub: return OfFloat(F(a(0)) - F(a(1)));
    case Op::kMul: return OfFloat(F(a(0)) * F(a(1)));
    case Op::kDiv: return OfFloat(F(a(0)) / F(a(1)));
    case Op::kFloor: return OfFloat(std::floor(F(a(0))));
    case Op::kSqrt: return OfFloat(std::sqrt(F(a(0))));
    case Op::kLess: return OfMask(F(a(0)) < F(a(1)));
    case Op::kGreater: return OfMask(F(a(0)) > F(a(1)));
    case Op::kGreaterEqual: return OfMask(F(a(0)) >= F(a(1)));
    case Op::kEqual: return OfMask(F(a(0)) == F(a(1)));
    case Op::kUnordered: return OfMask(std::isnan(F(a(0))) || std::isnan(F(a(1))));
    case Op::kSelect: return a(0).mask ? a(1) : a(2);
    case Op::kSelectZero: return a(0).mask ? a(1) : OfInt(0);
    case Op::kIntAdd: return {a(0).bits + a(1).bits};
    case Op::kIntSub: return {a(0).bits - a(1).bits};
    case Op::kIntAnd: return {a(0).bits & a(1).bits};
    case Op::kIntOr: return {a(0).bits | a(1).bits};
    case Op::kIntXor: return {a(0).bits ^ a(1).bits};
    case Op::kShiftLeft: return {a(0).bits << node.immediate};
    case Op::kShiftRight: return OfInt(I(a(0)) >> node.immediate);  // vpsrad: arithmetic
    case Op::kToInt: return OfInt(ConvertTruncating(F(a(0))));
    case Op::kToFloat: return OfFloat(static_cast<float>(I(a(0))));
    case Op::kIntGreater: return OfMask(I(a(0)) > I(a(1)));
    default: return {};
  }
}

Evaluation Evaluate(const Graph& graph, const std::vector<GroupData>& groups, const std::vector<float>& constants,
                    int constant_count) {
  Evaluation result;
  std::vector<Value> values;
  for (const Node& node : graph.nodes()) {
    const int group = static_cast<int>(node.immediate >> kGroupShift);
    const int lane = static_cast<int>(node.immediate & kLaneMask);
    Value value;
    switch (node.op) {
      case Op::kInput: {
        const auto it = groups[static_cast<std::size_t>(group)].inputs.find(lane);
        if (it == groups[static_cast<std::size_t>(group)].inputs.end()) {
          result.error = "a load of input lane " + std::to_string(lane) + ", which is absent or uniform";
          return result;
        }
        value = OfFloat(it->second);
        break;
      }
      case Op::kConstant: value = OfFloat(constants.at(node.immediate)); break;
      case Op::kLiteral: value = {node.immediate}; break;
      case Op::kConstantCount: value = OfInt(constant_count); break;
      case Op::kGather:
        value = OfFloat(constants.at(static_cast<std::size_t>(I(values[static_cast<std::size_t>(node.args[0])])) + node.immediate));
        break;
      case Op::kStore:
        if (!result.stores.emplace(node.immediate, F(values[static_cast<std::size_t>(node.args[0])])).second) {
          result.error = "output lane " + std::to_string(lane) + " stored twice";
        }
        break;
      default: value = EvaluateArithmetic(node, values); break;
    }
    values.push_back(value);
  }
  return result;
}

// The batch engine's constant table for `program` over `bank` (BatchEngine::SetConstants).
std::vector<float> ConstantTable(const Program& program, const ConstantBank& api_constants) {
  const ConstantBank bank = ApplyDefinitions(program, api_constants);
  std::vector<float> table(4 * static_cast<std::size_t>(batch::kFirstConstantRow + bank.size() + 64), 0.0f);
  for (int reg = 0; reg < bank.size(); ++reg) {
    for (int c = 0; c < 4; ++c) table[batch::ConstantIndex(reg, c)] = bank[reg][c];
  }
  return table;
}

bool SameFloat(float a, float b) { return Bits(a) == Bits(b) || (std::isnan(a) && std::isnan(b)); }

TEST(JitGraph, EvaluatesToTheReferenceEngineOnRandomProgramsInTwoGroups) {
  constexpr int kPrograms = 400, kGroups = 2, kVertices = 4;
  random_program::ProgramGenerator generator(20261126);
  for (int k = 0; k < kPrograms; ++k) {
    const Program program = generator.MakeProgram();
    const ConstantBank bank = generator.Constants();
    const VertexArrays inputs = generator.Inputs(kVertices * kGroups);
    // Every other program under the legacy rule, whose products the graph records as selects.
    const FloatRules rules = k % 2 == 0 ? FloatRules::kD3d9 : FloatRules::kLegacy;
    VertexArrays expected = MakeOutputArrays(kVertices * kGroups, program);
    ASSERT_EQ(MakeReferenceEngine(program, bank, rules)->Run(inputs, expected).message(), "");
    // As the batch engine compiles it: absent registers and lanes of one value are literals.
    std::vector<UniformInput> uniform;
    for (int reg = 0; reg < kInputRegisterCount; ++reg) {
      for (int c = 0; c < 4; ++c) {
        if (!inputs.has(reg)) {
          uniform.push_back({reg, c, kDefaultInput[c]});
        } else if (const std::optional<float> value = inputs.uniform(reg, c)) {
          uniform.push_back({reg, c, *value});
        }
      }
    }
    const Graph graph = RecordLoopBody(program, kGroups, uniform, rules);
    const std::vector<float> constants = ConstantTable(program, bank);
    const std::array<WriteMask, kOutputSlotCount> written = WrittenOutputLanes(program);
    for (int vertex = 0; vertex < kVertices; ++vertex) {
      std::vector<GroupData> groups(kGroups);
      for (int g = 0; g < kGroups; ++g) {
        for (int reg : inputs.registers()) {
          for (int c = 0; c < 4; ++c) groups[g].inputs[batch::InputLane(reg, c)] = inputs.lane(reg, c)[g * kVertices + vertex];
        }
      }
      const Evaluation evaluation = Evaluate(graph, groups, constants, bank.size());
      ASSERT_EQ(evaluation.error, "")
          << "program " << k << " (" << kFloatRulesNames.Name(rules) << ")\n" << Disassemble(program);
      for (int g = 0; g < kGroups; ++g) {
        for (int slot = 0; slot < kOutputSlotCount; ++slot) {
          for (int c = 0; c < 4; ++c) {
            const std::uint32_t key = static_cast<std::uint32_t>(batch::OutputLane(slot, c)) |
                                      static_cast<std::uint32_t>(g) << kGroupShift;
            const auto stored = evaluation.stores.find(key);
            ASSERT_EQ(stored != evaluation.stores.end(), written[slot].has(c))
                << "program " << k << " " << OutputSlotName(slot) << "." << kLaneLetters[c] << "\n" << Disassemble(program);
            if (stored == evaluation.stores.end()) continue;
            const float want = expected.lane(slot, c)[g * kVertices + vertex];
            ASSERT_TRUE(SameFloat(stored->second, want))
                << "program " << k << " (" << kFloatRulesNames.Name(rules) << ") group " << g << " vertex " << vertex << " " << OutputSlotName(slot) << "."
                << kLaneLetters[c] << ": graph " << stored->second << ", reference " << want << "\n" << Disassemble(program);
          }
        }
      }
    }
  }
}

Program Assemble(const std::string& body) {
  AssembleOptions options;
  options.validate = false;
  AssembleResult assembled = AssembleSource("vs.1.1\n" + body, "graph.vsh", options);
  EXPECT_TRUE(assembled.program.has_value()) << assembled.diagnostics.ToString();
  return assembled.program.value_or(Program{});
}

std::vector<const Node*> NodesOf(const Graph& graph, Op op) {
  std::vector<const Node*> nodes;
  for (const Node& node : graph.nodes()) {
    if (node.op == op) nodes.push_back(&node);
  }
  return nodes;
}

TEST(JitGraph, ALaneReadByThreeInstructionsIsLoadedOnce) {
  const Graph graph = RecordLoopBody(Assemble("dcl_position v0\n"
                                              "dp4 r0.x, v0, c0\n"
                                              "dp4 r0.y, v0, c1\n"
                                              "dp4 r0.z, v0, c2\n"
                                              "mov oPos, r0\n"),
                                     1, {}, FloatRules::kD3d9);
  EXPECT_EQ(NodesOf(graph, Op::kInput).size(), 4u);      // v0.xyzw
  EXPECT_EQ(NodesOf(graph, Op::kConstant).size(), 12u);  // c0..c2, four components each
  EXPECT_EQ(NodesOf(graph, Op::kStore).size(), 4u);
}

TEST(JitGraph, UniformInputsAreLiteralsNotLoads) {
  const Program program = Assemble("dcl_position v0\nmov oPos, v0\n");
  const std::vector<UniformInput> uniform = {{0, 1, 2.5f}};
  const Graph graph = RecordLoopBody(program, 1, uniform, FloatRules::kD3d9);
  std::set<std::uint32_t> loaded;
  for (const Node* node : NodesOf(graph, Op::kInput)) loaded.insert(node->immediate & kLaneMask);
  EXPECT_EQ(loaded, (std::set<std::uint32_t>{static_cast<std::uint32_t>(batch::InputLane(0, 0)),
                                             static_cast<std::uint32_t>(batch::InputLane(0, 2)),
                                             static_cast<std::uint32_t>(batch::InputLane(0, 3))}));
  const std::vector<const Node*> literals = NodesOf(graph, Op::kLiteral);
  EXPECT_TRUE(std::any_of(literals.begin(), literals.end(), [](const Node* n) { return n->immediate == Bits(2.5f); }));
}

TEST(JitGraph, EachGroupLoadsAndStoresItsOwnLanes) {
  constexpr int kGroups = 3;
  const Graph graph = RecordLoopBody(Assemble("dcl_position v0\nadd oPos, v0, c0\n"), kGroups, {}, FloatRules::kD3d9);
  std::map<std::uint32_t, int> loads_per_group, stores_per_group;
  for (const Node* node : NodesOf(graph, Op::kInput)) ++loads_per_group[node->immediate >> kGroupShift];
  for (const Node* node : NodesOf(graph, Op::kStore)) ++stores_per_group[node->immediate >> kGroupShift];
  for (std::uint32_t g = 0; g < kGroups; ++g) {
    EXPECT_EQ(loads_per_group[g], 4) << "group " << g;
    EXPECT_EQ(stores_per_group[g], 4) << "group " << g;
  }
  EXPECT_EQ(loads_per_group.size(), static_cast<std::size_t>(kGroups));
  // The constants are shared: one load of each component for all groups.
  EXPECT_EQ(NodesOf(graph, Op::kConstant).size(), 4u);
}

// A lane's groups are neighbouring vectors in its array: their stores side by side fill a cache line
// at once (what a streaming store needs, vm/engines/jit_compiler.h kCacheLineBytes).
TEST(JitGraph, TheGroupsStoresOfALaneAreAdjacent) {
  constexpr int kGroups = 2;
  const Graph graph = RecordLoopBody(Assemble("dcl_position v0\ndcl_normal v1\nadd oPos, v0, c0\n"
                                              "mul oD0, v1, c1\nmov oT0.xy, v1\n"),
                                     kGroups, {}, FloatRules::kD3d9);
  const std::vector<const Node*> stores = NodesOf(graph, Op::kStore);
  ASSERT_EQ(stores.size(), 10u * kGroups);
  for (std::size_t k = 0; k < stores.size(); k += kGroups) {
    for (int g = 0; g < kGroups; ++g) {
      EXPECT_EQ(stores[k + g]->immediate & kLaneMask, stores[k]->immediate & kLaneMask) << "store " << k + g;
      EXPECT_EQ(stores[k + g]->immediate >> kGroupShift, static_cast<std::uint32_t>(g)) << "store " << k + g;
    }
  }
}

TEST(JitGraph, RelativeReadsGatherOnlyAfterA0IsWritten) {
  const Graph before = RecordLoopBody(Assemble("dcl_position v0\nmov oPos, c[a0.x + 5]\n"), 1, {}, FloatRules::kD3d9);
  EXPECT_TRUE(NodesOf(before, Op::kGather).empty());
  std::set<std::uint32_t> read;
  for (const Node* node : NodesOf(before, Op::kConstant)) read.insert(node->immediate);
  EXPECT_EQ(read, (std::set<std::uint32_t>{batch::ConstantIndex(5, 0), batch::ConstantIndex(5, 1),
                                           batch::ConstantIndex(5, 2), batch::ConstantIndex(5, 3)}));

  const Graph after = RecordLoopBody(Assemble("dcl_position v0\nmov a0.x, v0.x\nmov oPos, c[a0.x + 5]\n"), 1, {}, FloatRules::kD3d9);
  const std::vector<const Node*> gathers = NodesOf(after, Op::kGather);
  ASSERT_EQ(gathers.size(), 4u);
  std::set<std::uint32_t> components;
  for (const Node* node : gathers) components.insert(node->immediate);
  EXPECT_EQ(components, (std::set<std::uint32_t>{0, 1, 2, 3}));
  EXPECT_EQ(NodesOf(after, Op::kConstantCount).size(), 1u);
  // The IR's one relative read (a row, then its lanes) is lowered away.
  EXPECT_TRUE(NodesOf(after, Op::kRelativeRow).empty());
  EXPECT_TRUE(NodesOf(after, Op::kComponent).empty());
}

}  // namespace
}  // namespace vs11::jit
