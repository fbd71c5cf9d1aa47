// vs11 translate (vm/translate): the recorded program computes what the reference engine computes, bit
// for bit, on random programs (the engines' differential generator); every program of programs/ and
// 300 generated ones translate to GLSL that glslang compiles and links for GLSL 3.30 and GLSL ES
// 3.00, and to SPIR-V that SPIRV-Tools validates; literals keep their bits; under --float-rules
// legacy every product of an instruction, and nothing else, follows the legacy rule.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "tests/vm/engines/random_program.h"
#include "vm/asm/assembler.h"
#include "vm/asm/disassembler.h"
#include "vm/engines/reference_engine.h"
#include "vm/reference/verify.h"
#include "vm/translate/glslang_compiler.h"
#include "vm/translate/shader_graph.h"
#include "vm/translate/translate.h"

namespace vs11::translate {
namespace {

namespace fs = std::filesystem;
using random_program::Bits;

// ---- the graph, evaluated: one C++ IEEE operation per node, as the GLSL statement performs it --------

struct Value {
  float f = 0.0f;
  std::int32_t i = 0;
  bool b = false;
  Vec4f v{};
};

std::int32_t Wrap(std::int64_t x) { return static_cast<std::int32_t>(static_cast<std::uint32_t>(x)); }

Value EvaluateNode(const ShaderGraph& graph, const ir::Node& node, const std::vector<Value>& values, const Vec4f* inputs,
                   const ConstantBank& bank) {
  auto f = [&](int k) { return values[static_cast<std::size_t>(node.args[static_cast<std::size_t>(k)])].f; };
  auto i = [&](int k) { return values[static_cast<std::size_t>(node.args[static_cast<std::size_t>(k)])].i; };
  Value out;
  switch (node.op) {
    case ir::Op::kLiteral:
      out.f = std::bit_cast<float>(node.immediate);
      out.i = static_cast<std::int32_t>(node.immediate);
      break;
    case ir::Op::kInput: out.f = inputs[node.immediate / 4][node.immediate % 4]; break;
    case ir::Op::kConstant: out.f = bank[static_cast<int>(node.immediate / 4)][node.immediate % 4]; break;
    case ir::Op::kRelativeRow: {
      const int row = i(0);
      const auto def = graph.definitions.find(row);
      if (row >= 0 && row < graph.constant_count) {
        if (def != graph.definitions.end()) {
          for (int c = 0; c < 4; ++c) out.v[c] = std::bit_cast<float>(def->second[c]);
        } else {
          out.v = bank[row];
        }
      }
      break;
    }
    case ir::Op::kComponent: out.f = values[static_cast<std::size_t>(node.args[0])].v[node.immediate]; break;
    case ir::Op::kAdd: out.f = f(0) + f(1); break;
    case ir::Op::kSub: out.f = f(0) - f(1); break;
    case ir::Op::kMul: out.f = f(0) * f(1); break;
    case ir::Op::kDiv: out.f = f(0) / f(1); break;
    case ir::Op::kFloor: out.f = std::floor(f(0)); break;
    case ir::Op::kSqrt: out.f = std::sqrt(f(0)); break;
    case ir::Op::kAbs: out.f = std::bit_cast<float>(Bits(f(0)) & 0x7FFFFFFFu); break;
    case ir::Op::kNegate: out.f = std::bit_cast<float>(Bits(f(0)) ^ 0x80000000u); break;
    case ir::Op::kUnordered: out.b = (Bits(f(0)) & 0x7FFFFFFFu) > 0x7F800000u || (Bits(f(1)) & 0x7FFFFFFFu) > 0x7F800000u; break;
    case ir::Op::kLess: out.b = f(0) < f(1); break;
    case ir::Op::kGreater: out.b = f(0) > f(1); break;
    case ir::Op::kGreaterEqual: out.b = f(0) >= f(1); break;
    case ir::Op::kEqual: out.b = f(0) == f(1); break;
    case ir::Op::kSelect: out.f = values[static_cast<std::size_t>(node.args[0])].b ? f(1) : f(2); break;
    case ir::Op::kBitsOf: out.i = std::bit_cast<std::int32_t>(f(0)); break;
    case ir::Op::kFloatFromBits: out.f = std::bit_cast<float>(i(0)); break;
    case ir::Op::kToInt: out.i = static_cast<std::int32_t>(f(0)); break;
    case ir::Op::kToFloat: out.f = static_cast<float>(i(0)); break;
    case ir::Op::kIntAdd: out.i = Wrap(std::int64_t{i(0)} + i(1)); break;
    case ir::Op::kIntSub: out.i = Wrap(std::int64_t{i(0)} - i(1)); break;
    case ir::Op::kIntAnd: out.i = i(0) & i(1); break;
    case ir::Op::kIntOr: out.i = i(0) | i(1); break;
    case ir::Op::kIntGreater: out.b = i(0) > i(1); break;
    case ir::Op::kShiftLeft: out.i = Wrap(static_cast<std::int64_t>(static_cast<std::uint32_t>(i(0)) << node.immediate)); break;
    case ir::Op::kShiftRight: out.i = i(0) >> node.immediate; break;
    default: ADD_FAILURE() << "the translator records no " << ir::OpName(node.op); break;
  }
  return out;
}

std::array<Vec4f, kOutputSlotCount> EvaluateGraph(const ShaderGraph& graph, const Vec4f* inputs, const ConstantBank& bank) {
  std::vector<Value> values;
  values.reserve(graph.graph.size());
  for (const ir::Node& node : graph.graph.nodes()) values.push_back(EvaluateNode(graph, node, values, inputs, bank));
  std::array<Vec4f, kOutputSlotCount> outputs{};
  for (int slot = 0; slot < kOutputSlotCount; ++slot) {
    for (int c = 0; c < 4; ++c) outputs[slot][c] = values[static_cast<std::size_t>(graph.outputs[slot][c])].f;
  }
  return outputs;
}

bool SameFloat(float a, float b) { return Bits(a) == Bits(b) || (std::isnan(a) && std::isnan(b)); }

// Under both float rules: each program is recorded and run under d3d9 and under legacy.
TEST(ShaderGraph, MatchesTheReferenceEngineOnRandomPrograms) {
  constexpr int kPrograms = 600, kVertices = 8;
  random_program::ProgramGenerator generator(20261125);
  for (int k = 0; k < kPrograms; ++k) {
    const Program program = generator.MakeProgram();
    const ConstantBank bank = generator.Constants();
    const VertexArrays inputs = generator.Inputs(kVertices);
    for (FloatRules rules : kAllFloatRules) {
      VertexArrays expected = MakeOutputArrays(kVertices, program);
      ASSERT_EQ(MakeReferenceEngine(program, bank, rules)->Run(inputs, expected).message(), "");
      const ShaderGraph graph = RecordShader(program, bank.size(), rules);
      for (int vertex = 0; vertex < kVertices; ++vertex) {
        std::array<Vec4f, kInputRegisterCount> vertex_inputs;
        vertex_inputs.fill(kDefaultInput);
        for (int reg : inputs.registers()) {
          for (int c = 0; c < 4; ++c) vertex_inputs[reg][c] = inputs.lane(reg, c)[vertex];
        }
        const auto outputs = EvaluateGraph(graph, vertex_inputs.data(), bank);
        for (int slot = 0; slot < kOutputSlotCount; ++slot) {
          for (int c = 0; c < 4; ++c) {
            const float want = expected.has(slot) ? expected.lane(slot, c)[vertex] : UnwrittenOutputValue(slot)[c];
            ASSERT_TRUE(SameFloat(outputs[slot][c], want))
                << kFloatRulesNames.Name(rules) << ", program " << k << " vertex " << vertex << " " << OutputSlotName(slot)
                << "." << kLaneLetters[c] << ": translation " << outputs[slot][c] << ", reference " << want << "\n"
                << Disassemble(program);
          }
        }
      }
    }
  }
}

// ---- the text: compiles for every target -----------------------------------------------------------

constexpr Target kTargets[] = {Target::kGlsl330, Target::kGlslEs300, Target::kGlslEs310, Target::kGlslEs320,
                               Target::kSpirv};

// Empty when `program` translates to text glslang compiles and links for every target and stage it
// can hold (vertex shaders for all, compute shaders for GLSL ES 3.10, 3.20 and SPIR-V), and for SPIR-V
// to words SPIRV-Tools validates; else what failed, with the text.
std::string CheckTranslations(const Program& program, const std::string& name, FloatRules rules) {
  for (Stage stage : {Stage::kVertex, Stage::kCompute}) {
    for (Target target : kTargets) {
      if (!StageProblem(target, stage).ok()) continue;
      const std::string glsl =
          TranslateToGlsl(program, {.target = target, .source_name = name, .float_rules = rules, .stage = stage});
      const Result<std::vector<std::uint32_t>> compiled = CompileWithGlslang(glsl, target, stage);
      const std::string what = fmt::format("{} {}", TargetName(target), StageName(stage));
      if (!compiled) return what + ": " + compiled.message() + "\n" + glsl;
      if (target != Target::kSpirv) continue;
      if (const Status valid = ValidateSpirv(*compiled); !valid.ok()) {
        return what + ": spirv-val: " + valid.message() + "\n" + glsl;
      }
    }
  }
  return "";
}

TEST(Translate, EveryProgramOfProgramsCompilesForEveryTarget) {
  int checked = 0;
  for (const fs::directory_entry& entry : fs::directory_iterator(fs::path(VS11_SOURCE_DIR) / "programs")) {
    if (entry.path().extension() != ".vsh") continue;
    const vs11::ProgramForVerify loaded = vs11::LoadProgramForVerify(entry.path());
    ASSERT_TRUE(loaded.program) << entry.path() << ": " << loaded.diagnostics.ToString();
    for (FloatRules rules : kAllFloatRules) {
      EXPECT_EQ(CheckTranslations(*loaded.program, entry.path().filename().string(), rules), "")
          << entry.path() << " under " << kFloatRulesNames.Name(rules);
    }
    ++checked;
  }
  EXPECT_GE(checked, 10) << "programs/ lost its programs";
}

// 300, or a tenth of VS11_DIFFERENTIAL_PROGRAMS where CI's sanitizer stage scales the random-program
// tests down (each program costs about 8 ms here, three compiles and a validation).
int GeneratedProgramCount() {
  const char* scaled = std::getenv("VS11_DIFFERENTIAL_PROGRAMS");
  return scaled != nullptr ? std::max(1, std::atoi(scaled) / 10) : 300;
}

// Odd programs under legacy, even ones under d3d9: both rules, at the cost of one.
TEST(Translate, GeneratedProgramsCompileForEveryTarget) {
  const int kPrograms = GeneratedProgramCount();
  random_program::ProgramGenerator generator(7);
  for (int k = 0; k < kPrograms; ++k) {
    const Program program = generator.MakeProgram();
    const FloatRules rules = k % 2 == 0 ? FloatRules::kD3d9 : FloatRules::kLegacy;
    ASSERT_EQ(CheckTranslations(program, "generated", rules), "")
        << "generated program " << k << " under " << kFloatRulesNames.Name(rules) << ":\n" << Disassemble(program);
  }
}

TranslateOptions Options(Target target, ClipSpace clip = ClipSpace::kTargetApi, int constant_count = kDefaultConstantCount) {
  TranslateOptions options;
  options.target = target;
  options.clip = clip;
  options.constant_count = constant_count;
  return options;
}

Program Assemble(const std::string& text) {
  AssembleOptions options;
  options.require_position = false;
  AssembleResult result = AssembleSource(text, "test.vsh", options);
  EXPECT_TRUE(result.program) << result.diagnostics.ToString();
  return result.program ? *result.program : Program{};
}

TEST(Translate, DefLiteralsAndSpecialValuesKeepTheirBits) {
  // -0 and a NaN with a payload survive only as bits; rcp of 0 is FLT_MAX (0x7F7FFFFF), exactly.
  Program program = Assemble("vs.1.1\ndef c3, -0, 1, 0.1, 0\nadd oD0, v0, c3\nrcp oT0, v1.x\n");
  program.instructions[0].def_bits[3] = 0x7FC12345u;
  const std::string glsl = TranslateToGlsl(program, {});
  for (const char* bits : {"0x80000000u", "0x3DCCCCCDu", "0x7FC12345u", "0x7F7FFFFFu"}) {
    EXPECT_NE(glsl.find(std::string("uintBitsToFloat(") + bits + ")"), std::string::npos) << bits << "\n" << glsl;
  }
  EXPECT_EQ(glsl.find("c[3]"), std::string::npos) << "a def wins over the bank\n" << glsl;
}

TEST(Translate, RelativeReadsSeeDefsAndTheBankEdge) {
  const std::string glsl = TranslateToGlsl(
      Assemble("vs_1_1\ndcl_position v0\ndef c5, 1, 2, 3, 4\nmov a0.x, v0.x\nmov oPos, c[a0.x + 2]\n"),
      Options(Target::kGlsl330, ClipSpace::kTargetApi, 100));
  EXPECT_NE(glsl.find("if (i < 0 || i >= 100) return vec4(0.0);"), std::string::npos) << glsl;
  EXPECT_NE(glsl.find("if (i == 5) return vec4(uintBitsToFloat(0x3F800000u)"), std::string::npos) << glsl;
  EXPECT_NE(glsl.find("uniform vec4 c[100];"), std::string::npos) << glsl;
  EXPECT_NE(glsl.find("layout(location = 0) in vec4 v0;  // dcl_position"), std::string::npos) << glsl;
}

// The multiplications that follow the legacy rule: a multiply of two selects that give 0 where the
// other operand is 0, the form of semantics::Product under FloatRules::kLegacy.
int CountLegacyProducts(const std::string& source) {
  const ShaderGraph graph =
      RecordShader(Assemble("vs.1.1\n" + source), kDefaultConstantCount, FloatRules::kLegacy);
  const std::vector<bool> live = LiveNodes(graph);
  auto is_zero_select = [&](int id) {
    const ir::Node& node = graph.graph[id];
    if (node.op != ir::Op::kSelect) return false;
    const ir::Node& yes = graph.graph[node.args[1]];
    return yes.op == ir::Op::kLiteral && yes.type == ir::Type::kFloat && yes.immediate == 0;
  };
  int products = 0;
  for (std::size_t n = 0; n < graph.graph.size(); ++n) {
    const ir::Node& node = graph.graph.nodes()[n];
    products += live[n] && node.op == ir::Op::kMul && is_zero_select(node.args[0]) && is_zero_select(node.args[1]);
  }
  return products;
}

// Under legacy, every product of an instruction's operands follows the rule, and exp's polynomial
// and 2^n scaling, which are not such products, do not.
TEST(Translate, LegacyRuleCoversEveryInstructionProductAndNothingElse) {
  EXPECT_EQ(CountLegacyProducts("mul oD0, v0, c1\n"), 4);
  EXPECT_EQ(CountLegacyProducts("mad oD0, v0, c1, v0\n"), 4);
  EXPECT_EQ(CountLegacyProducts("dp3 oD0, v0, c1\n"), 3);
  EXPECT_EQ(CountLegacyProducts("dp4 oD0, v0, c1\n"), 4);
  EXPECT_EQ(CountLegacyProducts("m4x4 oD0, v0, c0\n"), 16);
  EXPECT_EQ(CountLegacyProducts("m3x2 oD0.xy, v0, c0\n"), 6);
  EXPECT_EQ(CountLegacyProducts("dst oD0, v0, c1\n"), 1);
  EXPECT_EQ(CountLegacyProducts("lit oD0, v0\n"), 1);
  EXPECT_EQ(CountLegacyProducts("exp oD0, v0.x\n"), 0);
  EXPECT_EQ(CountLegacyProducts("expp oD0, v0.x\n"), 0);
}

TEST(Translate, InterfaceNamesTheFloatRules) {
  const Program program = Assemble("vs.1.1\nmul oD0, v0, c1\n");
  EXPECT_NE(TranslateToGlsl(program, {}).find("//   Float rules: d3d9"), std::string::npos);
  TranslateOptions options;
  options.float_rules = FloatRules::kLegacy;
  const std::string legacy = TranslateToGlsl(program, options);
  EXPECT_NE(legacy.find("//   Float rules: legacy"), std::string::npos) << legacy;
}

TEST(Translate, ClipSpaceConversions) {
  const Program program = Assemble("vs.1.1\nmov oPos, v0\n");
  EXPECT_NE(TranslateToGlsl(program, {}).find("gl_Position = vec4(vs11_oPos.xy, 2.0 * vs11_oPos.z - vs11_oPos.w"),
            std::string::npos);
  EXPECT_NE(TranslateToGlsl(program, Options(Target::kGlsl330, ClipSpace::kD3d)).find("gl_Position = vs11_oPos;"), std::string::npos);
  EXPECT_NE(TranslateToGlsl(program, Options(Target::kSpirv)).find("-vs11_oPos.y"), std::string::npos);
}

}  // namespace
}  // namespace vs11::translate
