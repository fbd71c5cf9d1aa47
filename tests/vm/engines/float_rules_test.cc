// --float-rules (vm/core/float_rules.h) on every engine: the reference engine, the batch engine at
// every Highway target this build compiled and the CPU runs, and the jit at every instruction set
// the CPU has (AVX2, AVX-512). An infinite constant times a zero lane is NaN under d3d9 and 0 under
// legacy in every instruction that multiplies, and the sign of a zero product is the one the README
// states. The differential tests (engine_differential_test.cc) compare the engines under both rules
// on random programs; these tests pin the values themselves, worked out by hand.
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "hwy/highway.h"
#include "hwy/tests/hwy_gtest.h"
#include "vm/asm/assembler.h"
#include "vm/core/float_rules.h"
#include "vm/engines/engine_factory.h"
#include "vm/engines/jit_compiler.h"
#include "tests/vm/engines/random_program.h"

namespace vs11 {
namespace {

using random_program::Bits;

constexpr float kInf = std::numeric_limits<float>::infinity();
const float kNaN = std::bit_cast<float>(0x7FC00000u);

Program AssembleOrDie(const std::string& source) {
  AssembleOptions options;
  options.require_position = false;
  AssembleResult result = AssembleSource(source, "float_rules.vsh", options);
  EXPECT_TRUE(result.program) << result.diagnostics.ToString();
  return result.program.value_or(Program{});
}

// Every instruction that multiplies its operands, each into its own output: c0 and the matrix rows
// c2..c5 hold infinities and NaN (no zeros), v0 zeros in vertex 0 and ordinary numbers in vertex 1,
// v1 makes lit's power 0 * log2(inf).
const char kEveryProduct[] =
    "vs.1.1\n"
    "mul oD0, c0, v0\n"
    "mov r0, v2\n"
    "mad oD1, c0, v0, r0\n"
    "dp3 oT0, c0, v0\n"
    "dp4 oT1, c0, v0\n"
    "m4x4 oT2, v0, c2\n"
    "m4x3 oT3.xyz, v0, c2\n"
    "m3x4 oT4, v0, c2\n"
    "m3x3 oT5.xyz, v0, c2\n"
    "m3x2 oT6.xy, v0, c2\n"
    "dst oT7, c0, v0\n"
    "lit oPos, v1\n";

ConstantBank InfiniteConstants() {
  ConstantBank bank;
  bank[0] = {kInf, -kInf, -kInf, kNaN};
  for (int row = 2; row <= 5; ++row) bank[row] = {kInf, -kInf, row % 2 ? kNaN : kInf, -kInf};
  return bank;
}

VertexArrays ZeroThenOrdinaryInputs() {
  const int registers[] = {0, 1, 2};
  VertexArrays inputs = MakeInputArrays(2, registers);
  const Vec4f v0[2] = {{0.0f, -0.0f, 0.0f, 0.0f}, {1.0f, -2.0f, 0.5f, 4.0f}};
  const Vec4f v1[2] = {{1.0f, kInf, 0.0f, 0.0f} /* lit: x > 0, y = inf, power 0 */, {1.0f, 2.0f, 0.0f, 3.0f}};
  const Vec4f v2 = {1.0f, 2.0f, 3.0f, 4.0f};
  for (std::size_t i = 0; i < 2; ++i) {
    for (int c = 0; c < 4; ++c) {
      inputs.lane(0, c)[i] = v0[i][c];
      inputs.lane(1, c)[i] = v1[i][c];
      inputs.lane(2, c)[i] = v2[c];
    }
  }
  return inputs;
}

struct Lane {
  OutputSlot slot;
  int component;
  float legacy;  // vertex 0 under legacy
};

OutputSlot TexCoord(int n) { return static_cast<OutputSlot>(static_cast<int>(OutputSlot::kTexCoord0) + n); }

// Vertex 0 by hand. Every product has a zero operand, so under legacy it is zero: +0 for v0's +0
// lanes, -0 for (-inf) * (-0) (the zero operand's sign). Sums of them are +0 (+0 + -0 = +0); mad adds
// v2; dst is (1, c0.y * v0.y, c0.z, v0.w); lit's power 0 * log2(inf) is 0, so its z is 2^0 = 1.
std::vector<std::pair<Lane, bool>> ProductLanes() {
  std::vector<std::pair<Lane, bool>> lanes;  // the lane, and whether it is a product (NaN under d3d9)
  auto add = [&](OutputSlot slot, int component, float legacy, bool product = true) {
    lanes.push_back({{slot, component, legacy}, product});
  };
  const float zeros[4] = {0.0f, -0.0f, 0.0f, 0.0f};
  for (int c = 0; c < 4; ++c) add(OutputSlot::kDiffuse, c, zeros[c]);
  for (int c = 0; c < 4; ++c) add(OutputSlot::kSpecular, c, static_cast<float>(c + 1));
  for (int c = 0; c < 4; ++c) add(TexCoord(0), c, 0.0f);  // dp3
  for (int c = 0; c < 4; ++c) add(TexCoord(1), c, 0.0f);  // dp4
  const int rows[5] = {4, 3, 4, 3, 2};                     // m4x4 m4x3 m3x4 m3x3 m3x2
  for (int m = 0; m < 5; ++m) {
    for (int c = 0; c < rows[m]; ++c) add(TexCoord(2 + m), c, 0.0f);
  }
  add(TexCoord(7), 0, 1.0f, false);
  add(TexCoord(7), 1, -0.0f);
  add(TexCoord(7), 2, -kInf, false);
  add(TexCoord(7), 3, 0.0f, false);
  add(OutputSlot::kPosition, 0, 1.0f, false);
  add(OutputSlot::kPosition, 1, 1.0f, false);
  add(OutputSlot::kPosition, 2, 1.0f);  // lit's power
  add(OutputSlot::kPosition, 3, 1.0f, false);
  return lanes;
}

// An engine made by MakeEngine: its kind and, for the jit, the instruction set.
struct EngineUnderTest {
  std::string kind;
  JitIsa jit_isa = JitIsa::kBest;
  std::string label;
};

VertexArrays Run(const EngineUnderTest& engine, const Program& program, const ConstantBank& bank,
                 const VertexArrays& inputs, FloatRules rules) {
  VertexArrays outputs = MakeOutputArrays(inputs.count(), program);
  EXPECT_EQ(MakeEngine(engine.kind, program, bank, WithJitIsa({.float_rules = rules}, engine.jit_isa))
                .value()
                ->Run(inputs, outputs)
                .message(),
            "");
  return outputs;
}

void CheckInfinityTimesZero(const EngineUnderTest& engine) {
  SCOPED_TRACE(engine.label);
  const Program program = AssembleOrDie(kEveryProduct);
  const ConstantBank bank = InfiniteConstants();
  const VertexArrays inputs = ZeroThenOrdinaryInputs();
  const VertexArrays d3d9 = Run(engine, program, bank, inputs, FloatRules::kD3d9);
  const VertexArrays legacy = Run(engine, program, bank, inputs, FloatRules::kLegacy);
  for (const auto& [lane, product] : ProductLanes()) {
    const int slot = static_cast<int>(lane.slot);
    const std::string name = OutputSlotName(slot) + "." + kLaneLetters[lane.component];
    const float under_d3d9 = d3d9.lane(slot, lane.component)[0], under_legacy = legacy.lane(slot, lane.component)[0];
    if (product) {
      EXPECT_TRUE(std::isnan(under_d3d9)) << name << " under d3d9: " << under_d3d9;
    } else {
      EXPECT_EQ(Bits(under_d3d9), Bits(lane.legacy)) << name << " under d3d9 (not a product)";
    }
    EXPECT_EQ(Bits(under_legacy), Bits(lane.legacy)) << name << " under legacy: " << under_legacy << ", expected "
                                                     << lane.legacy;
    // Vertex 1 has no zero operand: both rules give the same bits, but for which of two NaNs a sum
    // of NaNs returns (IEEE leaves it open; see engine_differential_test.cc's NanBits).
    const float d3d9_ordinary = d3d9.lane(slot, lane.component)[1], legacy_ordinary = legacy.lane(slot, lane.component)[1];
    if (!(std::isnan(d3d9_ordinary) && std::isnan(legacy_ordinary))) {
      EXPECT_EQ(Bits(d3d9_ordinary), Bits(legacy_ordinary)) << name << " with no zero operand";
    }
  }
}

// The rule in words, as the README states it: a zero operand makes the product zero, with the zero
// operand's sign when the other operand is not zero and +0 when both are; otherwise IEEE.
float LegacyProductAsDocumented(float a, float b) {
  if (a == 0.0f && b == 0.0f) return 0.0f;
  if (a == 0.0f) return a;
  if (b == 0.0f) return b;
  return a * b;
}

// mul over every pair of the differential tests' special values (zeros of both signs, denormals,
// infinities, NaNs): legacy as documented, d3d9 as IEEE; a NaN result may be any NaN where both
// operands are NaNs (IEEE leaves open which one an operation returns).
void CheckSignsOfZeroProducts(const EngineUnderTest& engine) {
  SCOPED_TRACE(engine.label);
  const std::vector<float>& values = random_program::SpecialValues();
  const std::size_t n = values.size();
  const VertexArrays inputs = random_program::EveryPairOf(values);
  const Program program = AssembleOrDie("vs.1.1\nmov r0, v1\nmul oD0, v0, r0\n");
  for (FloatRules rules : kAllFloatRules) {
    const VertexArrays outputs = Run(engine, program, ConstantBank(), inputs, rules);
    for (std::size_t i = 0; i < n * n; ++i) {
      const float a = values[i / n], b = values[i % n];
      const float want = rules == FloatRules::kLegacy ? LegacyProductAsDocumented(a, b) : a * b;
      const float got = outputs.lane(static_cast<int>(OutputSlot::kDiffuse), 0)[i];
      if (std::isnan(a) && std::isnan(b) && std::isnan(want) && std::isnan(got)) continue;
      EXPECT_EQ(Bits(got), Bits(want)) << kFloatRulesNames.Name(rules) << ": " << a << " * " << b << " gave " << got
                                       << ", expected " << want;
    }
  }
}

TEST(FloatRules, ReferenceEngineMakesInfinityTimesZeroNaNOrZero) {
  CheckInfinityTimesZero({"ref", JitIsa::kBest, "ref"});
}

TEST(FloatRules, ReferenceEngineGivesTheDocumentedSignOfZero) {
  CheckSignsOfZeroProducts({"ref", JitIsa::kBest, "ref"});
}

class FloatRulesBatch : public hwy::TestWithParamTarget {};
HWY_TARGET_INSTANTIATE_TEST_SUITE_P(FloatRulesBatch);

TEST_P(FloatRulesBatch, InfinityTimesZeroIsNaNOrZero) {
  CheckInfinityTimesZero({"batch", JitIsa::kBest, std::string("batch ") + hwy::TargetName(GetParam())});
}

TEST_P(FloatRulesBatch, SignOfZeroAsDocumented) {
  CheckSignsOfZeroProducts({"batch", JitIsa::kBest, std::string("batch ") + hwy::TargetName(GetParam())});
}

class FloatRulesJit : public testing::TestWithParam<JitIsa> {
 protected:
  EngineUnderTest Engine() const { return {"jit", GetParam(), std::string("jit ") + std::string(kJitIsaNames.Name(GetParam()))}; }
};
INSTANTIATE_TEST_SUITE_P(SupportedIsas, FloatRulesJit, testing::ValuesIn(jit::SupportedIsas()),
                         [](const testing::TestParamInfo<JitIsa>& info) { return std::string(kJitIsaNames.Name(info.param)); });
// A CPU without AVX2 has no instance: there the jit engine runs the batch kernels, tested above.
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(FloatRulesJit);

TEST_P(FloatRulesJit, InfinityTimesZeroIsNaNOrZero) {
  // The jit engine falls back to the kernels where it cannot compile: make sure it compiled.
  std::string why_not;
  ASSERT_NE(jit::Compile(AssembleOrDie(kEveryProduct), why_not, GetParam(), {}, FloatRules::kLegacy), nullptr) << why_not;
  CheckInfinityTimesZero(Engine());
}

TEST_P(FloatRulesJit, SignOfZeroAsDocumented) { CheckSignsOfZeroProducts(Engine()); }

TEST(FloatRules, NamesRoundTrip) {
  for (FloatRules rules : kAllFloatRules) EXPECT_EQ(kFloatRulesNames.Find(kFloatRulesNames.Name(rules)), rules);
  EXPECT_EQ(kFloatRulesNames.Name(FloatRules::kD3d9), "d3d9");
  EXPECT_EQ(kFloatRulesNames.Name(FloatRules::kLegacy), "legacy");
  EXPECT_FALSE(kFloatRulesNames.Find("strict").has_value());
  EXPECT_EQ(EngineOptions().float_rules, FloatRules::kD3d9);
}

}  // namespace
}  // namespace vs11
