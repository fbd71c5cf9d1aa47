// Per-instruction execution on the reference interpreter, with expected values worked out by hand
// from the spec's pseudo-code (../shared/spec/vs_1_1.md §3.3), special values included.
#include "vm/engines/engine_factory.h"
#include "vm/engines/reference_engine.h"

#include <bit>
#include <cfloat>
#include <cmath>
#include <initializer_list>
#include <string>

#include <gtest/gtest.h>

#include "vm/asm/assembler.h"

namespace vs11 {
namespace {

using ::testing::Test;

// Assembles `body` after a `vs.1.1` line (validation off: these are single-instruction probes) and
// runs it on one vertex.
VertexState Execute(const std::string& body, ConstantBank constants = ConstantBank(),
                    std::initializer_list<std::pair<int, Vec4f>> inputs = {}) {
  AssembleOptions options;
  options.validate = false;
  AssembleResult assembled = AssembleSource("vs.1.1\n" + body, "probe.vsh", options);
  EXPECT_TRUE(assembled.program.has_value()) << assembled.diagnostics.ToString();
  VertexState state;
  state.inputs.fill(kDefaultInput);
  for (const auto& [reg, value] : inputs) state.inputs[reg] = value;
  if (assembled.program) RunVertex(*assembled.program, ApplyDefinitions(*assembled.program, constants), state);
  return state;
}

ConstantBank Constants(std::initializer_list<std::pair<int, Vec4f>> values) {
  ConstantBank bank;
  for (const auto& [index, value] : values) bank[index] = value;
  return bank;
}

std::uint32_t Bits(float x) { return std::bit_cast<std::uint32_t>(x); }

void ExpectBitsEqual(const Vec4f& actual, const Vec4f& expected) {
  for (int lane = 0; lane < 4; ++lane) {
    EXPECT_EQ(Bits(actual[lane]), Bits(expected[lane]))
        << "lane " << lane << ": " << actual[lane] << " vs expected " << expected[lane];
  }
}

TEST(ReferenceEngine, MovCopiesWithSwizzleAndNegation) {
  VertexState s = Execute("mov r0, -v1.wzyx\n", ConstantBank(), {{1, {1, 2, 3, 4}}});
  ExpectBitsEqual(s.temps[0], {-4, -3, -2, -1});
}

TEST(ReferenceEngine, WriteMaskLeavesOtherLanes) {
  VertexState s = Execute("mov r0, c0\nmov r0.yw, c1\n", Constants({{0, {1, 2, 3, 4}}, {1, {5, 6, 7, 8}}}));
  ExpectBitsEqual(s.temps[0], {1, 6, 3, 8});
}

TEST(ReferenceEngine, ShortSwizzleRepeatsLastLetter) {
  VertexState s = Execute("mov r0, c0.xy\n", Constants({{0, {1, 2, 3, 4}}}));
  ExpectBitsEqual(s.temps[0], {1, 2, 2, 2});
}

TEST(ReferenceEngine, AddReadsAllSourcesBeforeWriting) {
  VertexState s = Execute("mov r0, c0\nadd r0, r0.yzwx, r0\n", Constants({{0, {1, 2, 3, 4}}}));
  ExpectBitsEqual(s.temps[0], {3, 5, 7, 5});
}

TEST(ReferenceEngine, SubAndMul) {
  VertexState s = Execute("sub r0, c0, c0.x\nmul r1, c0, c0.w\n", Constants({{0, {1, 2, 3, 4}}}));
  ExpectBitsEqual(s.temps[0], {0, 1, 2, 3});
  ExpectBitsEqual(s.temps[1], {4, 8, 12, 16});
}

TEST(ReferenceEngine, MadIsNotFused) {
  // a*b = 1 + 2^-11 + 2^-24 rounds to 1 + 2^-11 (tie to even); adding -(1 + 2^-11) gives 0. A fused
  // multiply-add would keep the 2^-24.
  float a = 1.0f + std::ldexp(1.0f, -12);
  float c = -(1.0f + std::ldexp(1.0f, -11));
  VertexState s = Execute("mad r0, c0, c0, c1\n", Constants({{0, {a, a, a, a}}, {1, {c, c, c, c}}}));
  ExpectBitsEqual(s.temps[0], {0, 0, 0, 0});
}

TEST(ReferenceEngine, Dp3IgnoresWAndReplicates) {
  VertexState s = Execute("dp3 r0, c0, c1\n", Constants({{0, {1, 2, 3, 100}}, {1, {4, 5, 6, 100}}}));
  ExpectBitsEqual(s.temps[0], {32, 32, 32, 32});
}

TEST(ReferenceEngine, Dp4SumsFourLanesToMaskedLanes) {
  VertexState s = Execute("mov r0, c2\ndp4 r0.xz, c0, c1\n",
                          Constants({{0, {1, 2, 3, 4}}, {1, {5, 6, 7, 8}}, {2, {-1, -1, -1, -1}}}));
  ExpectBitsEqual(s.temps[0], {70, -1, 70, -1});
}

TEST(ReferenceEngine, Dp4SumsLeftToRight) {
  // ((1e8 + 1) - 1e8) + 1 in float: 1e8 + 1 rounds to 1e8, so the sum is 1, not 2.
  VertexState s = Execute("dp4 r0, c0, c1\n", Constants({{0, {1e8f, 1, -1e8f, 1}}, {1, {1, 1, 1, 1}}}));
  EXPECT_EQ(s.temps[0][0], 1.0f);
}

TEST(ReferenceEngine, MinMaxSltSge) {
  ConstantBank c = Constants({{0, {1, 5, -2, 3}}, {1, {2, 5, -3, 3}}});
  VertexState s = Execute("min r0, c0, c1\nmax r1, c0, c1\nslt r2, c0, c1\nsge r3, c0, c1\n", c);
  ExpectBitsEqual(s.temps[0], {1, 5, -3, 3});
  ExpectBitsEqual(s.temps[1], {2, 5, -2, 3});
  ExpectBitsEqual(s.temps[2], {1, 0, 0, 0});
  ExpectBitsEqual(s.temps[3], {0, 1, 1, 1});
}

TEST(ReferenceEngine, MinMaxWithNaNFollowTheComparisons) {
  // min: a < b ? a : b; max: a >= b ? a : b. Any comparison with NaN is false, so both give b.
  float nan = std::numeric_limits<float>::quiet_NaN();
  VertexState s = Execute("min r0, c0, c1\nmax r1, c0, c1\nmin r2, c1, c0\n",
                          Constants({{0, {nan, nan, nan, nan}}, {1, {2, 2, 2, 2}}}));
  EXPECT_EQ(s.temps[0][0], 2.0f);
  EXPECT_EQ(s.temps[1][0], 2.0f);
  EXPECT_TRUE(std::isnan(s.temps[2][0]));
}

TEST(ReferenceEngine, RcpSpecialCases) {
  ConstantBank c = Constants({{0, {0, 1, 2, -4}}, {1, {0, 0, 0, -0.0f}}});
  VertexState s = Execute("rcp r0, c0.x\nrcp r1, c0.y\nrcp r2, c0.z\nrcp r3, c0\nrcp r4, c1.w\n", c);
  ExpectBitsEqual(s.temps[0], {FLT_MAX, FLT_MAX, FLT_MAX, FLT_MAX});
  ExpectBitsEqual(s.temps[1], {1, 1, 1, 1});
  ExpectBitsEqual(s.temps[2], {0.5f, 0.5f, 0.5f, 0.5f});
  ExpectBitsEqual(s.temps[3], {-0.25f, -0.25f, -0.25f, -0.25f});  // no swizzle: the w lane
  ExpectBitsEqual(s.temps[4], {FLT_MAX, FLT_MAX, FLT_MAX, FLT_MAX});  // -0 gives +FLT_MAX
}

TEST(ReferenceEngine, RsqTakesAbsoluteValue) {
  ConstantBank c = Constants({{0, {4, -4, 0, 1}}});
  VertexState s = Execute("rsq r0, c0.x\nrsq r1, c0.y\nrsq r2, c0.z\nrsq r3, c0.w\n", c);
  EXPECT_EQ(s.temps[0][0], 0.5f);
  EXPECT_EQ(s.temps[1][0], 0.5f);
  EXPECT_EQ(s.temps[2][0], FLT_MAX);
  EXPECT_EQ(s.temps[3][0], 1.0f);
}

TEST(ReferenceEngine, ExpOfIntegersIsExact) {
  ConstantBank c = Constants({{0, {3, -2, 0, 10}}});
  VertexState s = Execute("exp r0.x, c0.x\nexp r0.y, c0.y\nexp r0.z, c0.z\nexp r0.w, c0.w\n", c);
  ExpectBitsEqual(s.temps[0], {8, 0.25f, 1, 1024});
}

TEST(ReferenceEngine, ExpOverflowsAndUnderflows) {
  float inf = std::numeric_limits<float>::infinity();
  ConstantBank c = Constants({{0, {200, -200, inf, -inf}}});
  VertexState s = Execute("exp r0.x, c0.x\nexp r0.y, c0.y\nexp r0.z, c0.z\nexp r0.w, c0.w\n", c);
  ExpectBitsEqual(s.temps[0], {inf, 0, inf, 0});
}

TEST(ReferenceEngine, ExpAndLogMeetTwentyOneBitsOverAWideRange) {
  // §3.3: exp and log are full precision to at least 21 bits.
  const double kTolerance = std::ldexp(1.0, -21);
  double worst_exp = 0.0, worst_log = 0.0;
  for (int i = 0; i < 4000; ++i) {
    float x = -120.0f + 240.0f * static_cast<float>(i) / 4000.0f + 0.0137f;
    VertexState s = Execute("exp r0, c0.x\n", Constants({{0, {x, 0, 0, 0}}}));
    double exact = std::exp2(static_cast<double>(x));
    worst_exp = std::max(worst_exp, std::fabs(s.temps[0][0] - exact) / exact);
    float v = std::ldexp(1.0f + static_cast<float>(i % 1000) / 1000.0f, i / 1000 * 20 - 40);
    VertexState t = Execute("log r0, c0.x\n", Constants({{0, {v, 0, 0, 0}}}));
    double exact_log = std::log2(static_cast<double>(v));
    worst_log = std::max(worst_log, std::fabs(t.temps[0][0] - exact_log) / std::max(1.0, std::fabs(exact_log)));
  }
  EXPECT_LT(worst_exp, kTolerance);
  EXPECT_LT(worst_log, kTolerance);
}

TEST(ReferenceEngine, LogSpecialCases) {
  float inf = std::numeric_limits<float>::infinity();
  ConstantBank c = Constants({{0, {8, -8, 0, inf}}, {1, {0.5f, 1, std::ldexp(1.0f, -140), 0}}});
  VertexState s = Execute("log r0.x, c0.x\nlog r0.y, c0.y\nlog r0.z, c0.z\nlog r0.w, c0.w\n"
                          "log r1.x, c1.x\nlog r1.y, c1.y\nlog r1.z, c1.z\n", c);
  ExpectBitsEqual(s.temps[0], {3, 3, -FLT_MAX, inf});
  EXPECT_EQ(s.temps[1][0], -1.0f);
  EXPECT_EQ(s.temps[1][1], 0.0f);
  EXPECT_EQ(s.temps[1][2], -140.0f);  // a denormal input still gives its exact exponent
}

TEST(ReferenceEngine, LitCases) {
  // s = (N.L, N.H, -, exponent)
  ConstantBank c = Constants({{0, {-0.5f, 0.5f, 0, 2}}, {1, {0.75f, -0.5f, 0, 2}}, {2, {0.75f, 0.5f, 0, 2}},
                              {3, {1, 0.5f, 0, 300}}, {4, {1, 2, 0, -300}}});
  VertexState s = Execute("lit r0, c0\nlit r1, c1\nlit r2, c2\nlit r3, c3\nlit r4, c4\n", c);
  ExpectBitsEqual(s.temps[0], {1, 0, 0, 1});
  ExpectBitsEqual(s.temps[1], {1, 0.75f, 0, 1});
  EXPECT_EQ(s.temps[2][1], 0.75f);
  EXPECT_NEAR(s.temps[2][2], 0.25f, 1e-6f);
  // The exponent clamps to +-127.9961: 0.5^127.9961 and 2^-127.9961.
  EXPECT_NEAR(s.temps[3][2] / std::exp2(-127.9961), 1.0, 1e-5);
  EXPECT_NEAR(s.temps[4][2] / std::exp2(-127.9961), 1.0, 1e-5);
}

TEST(ReferenceEngine, DstBuildsDistanceVector) {
  // s0 = (-, d^2, d^2, -), s1 = (-, 1/d, -, 1/d) with d = 4.
  VertexState s = Execute("dst r0, c0, c1\n", Constants({{0, {9, 16, 16, 9}}, {1, {9, 0.25f, 9, 0.25f}}}));
  ExpectBitsEqual(s.temps[0], {1, 4, 16, 0.25f});
}

TEST(ReferenceEngine, FrcOfNegativeIsPositiveFraction) {
  VertexState s = Execute("mov r0, c1\nfrc r0.xy, c0\n", Constants({{0, {-0.25f, 1.5f, 7, 7}}, {1, {9, 9, 9, 9}}}));
  ExpectBitsEqual(s.temps[0], {0.75f, 0.5f, 9, 9});
}

TEST(ReferenceEngine, MatrixMacrosUseConsecutiveRows) {
  ConstantBank c = Constants({{0, {1, 2, 3, 4}}, {4, {1, 0, 0, 0}}, {5, {0, 2, 0, 0}}, {6, {0, 0, 3, 0}}, {7, {1, 1, 1, 1}}});
  VertexState s = Execute("m4x4 r0, c0, c4\nm4x3 r1.xyz, c0, c4\nm3x4 r2, c0, c4\nm3x3 r3.xyz, c0, c4\n"
                          "mov r4, c0.w\nm3x2 r4.xy, c0, c4\n", c);
  ExpectBitsEqual(s.temps[0], {1, 4, 9, 10});
  ExpectBitsEqual(s.temps[1], {1, 4, 9, 0});
  ExpectBitsEqual(s.temps[2], {1, 4, 9, 6});  // dp3 rows: w of the input is ignored
  ExpectBitsEqual(s.temps[3], {1, 4, 9, 0});
  ExpectBitsEqual(s.temps[4], {1, 4, 4, 4});  // m3x2 leaves z and w alone
}

TEST(ReferenceEngine, ExppSplitsExponentAndFraction) {
  VertexState s = Execute("expp r0, c0.x\n", Constants({{0, {2.5f, 0, 0, 0}}}));
  EXPECT_EQ(s.temps[0][0], 4.0f);
  EXPECT_EQ(s.temps[0][1], 0.5f);
  EXPECT_NEAR(s.temps[0][2], std::exp2(2.5), std::ldexp(1.0, -11) * 8);
  EXPECT_EQ(Bits(s.temps[0][2]) & 0xFF, 0u);  // the low 8 mantissa bits are cleared
  EXPECT_EQ(s.temps[0][3], 1.0f);
}

TEST(ReferenceEngine, ExppOfNegativeInput) {
  VertexState s = Execute("expp r0, c0.x\n", Constants({{0, {-1.25f, 0, 0, 0}}}));
  EXPECT_EQ(s.temps[0][0], 0.25f);  // 2^floor(-1.25) = 2^-2
  EXPECT_EQ(s.temps[0][1], 0.75f);
  EXPECT_NEAR(s.temps[0][2], std::exp2(-1.25), 1e-3);
}

TEST(ReferenceEngine, LogpSplitsExponentAndMantissa) {
  VertexState s = Execute("logp r0, c0.x\nlogp r1, c0.y\nlogp r2, -c0.z\n", Constants({{0, {8, 12, 0, 0}}}));
  ExpectBitsEqual(s.temps[0], {3, 1, 3, 1});
  EXPECT_EQ(s.temps[1][0], 3.0f);
  EXPECT_EQ(s.temps[1][1], 1.5f);
  EXPECT_NEAR(s.temps[1][2], std::log2(12.0), std::ldexp(1.0, -11) * 4);
  EXPECT_EQ(Bits(s.temps[1][2]) & 0xFF, 0u);
  ExpectBitsEqual(s.temps[2], {-FLT_MAX, 1, -FLT_MAX, 1});  // logp(0), -0 included
}

TEST(ReferenceEngine, AddressRegisterFloorsAndIndexesConstants) {
  ConstantBank c = Constants({{0, {2.7f, -0.5f, 200, 0}}, {5, {5, 5, 5, 5}}, {2, {2, 2, 2, 2}}});
  VertexState s = Execute("mov a0.x, c0.x\nmov r0, c[a0.x + 3]\nmov a0.x, c0.y\nmov r1, c[a0.x + 3]\n"
                          "mov a0.x, c0.z\nmov r2, c[a0.x + 3]\n", c);
  ExpectBitsEqual(s.temps[0], {5, 5, 5, 5});  // floor(2.7) + 3 = 5
  ExpectBitsEqual(s.temps[1], {2, 2, 2, 2});  // floor(-0.5) + 3 = 2
  ExpectBitsEqual(s.temps[2], {0, 0, 0, 0});  // 203 is past c95: reads 0
}

TEST(ReferenceEngine, NegativeRelativeIndexReadsZero) {
  VertexState s = Execute("mov a0.x, c0.x\nmov r0, c[a0.x + 1]\n", Constants({{0, {-5, 1, 1, 1}}}));
  ExpectBitsEqual(s.temps[0], {0, 0, 0, 0});
}

TEST(ReferenceEngine, AddressFromNaNIsOutOfRange) {
  EXPECT_EQ(AddressFromFloat(std::numeric_limits<float>::quiet_NaN()), -(1 << 20));
  EXPECT_EQ(AddressFromFloat(1e30f), 1 << 20);
  EXPECT_EQ(AddressFromFloat(-1.5f), -2);
}

TEST(ReferenceEngine, DefOverridesApiConstants) {
  VertexState s = Execute("def c3, 1, 2, 3, 4\nmov r0, c3\n", Constants({{3, {9, 9, 9, 9}}}));
  ExpectBitsEqual(s.temps[0], {1, 2, 3, 4});
}

TEST(ReferenceEngine, UnsuppliedInputsReadZeroZeroZeroOne) {
  VertexState s = Execute("mov r0, v7\n");
  ExpectBitsEqual(s.temps[0], {0, 0, 0, 1});
}

TEST(ReferenceEngine, NopChangesNothing) {
  VertexState s = Execute("mov r0, c0\nnop\n", Constants({{0, {1, 2, 3, 4}}}));
  ExpectBitsEqual(s.temps[0], {1, 2, 3, 4});
}

TEST(ReferenceEngine, OutputsReceiveMaskedWrites) {
  VertexState s = Execute("mov oPos, c0\nmov oD0.xyz, c0.w\nmov oT3.xy, c0\nmov oFog, c0.z\n", Constants({{0, {1, 2, 3, 4}}}));
  ExpectBitsEqual(s.outputs[static_cast<int>(OutputSlot::kPosition)], {1, 2, 3, 4});
  ExpectBitsEqual(s.outputs[static_cast<int>(OutputSlot::kDiffuse)], {4, 4, 4, 0});
  ExpectBitsEqual(s.outputs[static_cast<int>(OutputSlot::kTexCoord0) + 3], {1, 2, 0, 0});
  EXPECT_EQ(s.outputs[static_cast<int>(OutputSlot::kFog)][0], 3.0f);
}

TEST(ReferenceEngine, EngineFillsUnwrittenOutputsWithDefaults) {
  AssembleResult assembled = AssembleSource("vs.1.1\nmov oPos, v0\nmov oD1.x, v0.x\n", "t.vsh", {});
  ASSERT_TRUE(assembled.program) << assembled.diagnostics.ToString();
  std::vector<int> registers = {0};
  VertexArrays inputs = MakeInputArrays(2, registers);
  inputs.lane(0, 0)[1] = 5.0f;
  VertexArrays outputs = MakeOutputArrays(2, *assembled.program);
  ASSERT_EQ(MakeEngine("ref", *assembled.program, ConstantBank()).value()->Run(inputs, outputs).message(), "");
  EXPECT_TRUE(outputs.has(static_cast<int>(OutputSlot::kPosition)));
  EXPECT_FALSE(outputs.has(static_cast<int>(OutputSlot::kDiffuse)));
  EXPECT_EQ(outputs.lane(static_cast<int>(OutputSlot::kPosition), 0)[1], 5.0f);
  EXPECT_EQ(outputs.lane(static_cast<int>(OutputSlot::kPosition), 3)[1], 1.0f);
  EXPECT_EQ(outputs.lane(static_cast<int>(OutputSlot::kSpecular), 0)[1], 5.0f);
  EXPECT_EQ(outputs.lane(static_cast<int>(OutputSlot::kSpecular), 3)[1], 0.0f);  // partly written: 0
}

TEST(ReferenceEngine, ManyDefinitionsGiveTheLastValueOfEachRegisterToEveryVertex) {
  std::string text = "vs.1.1\n";  // unvalidated: 4096 defs, each register defined 1024 times
  for (int i = 0; i < 4096; ++i) text += "def c" + std::to_string(i % 4) + ", " + std::to_string(i) + ", 0, 0, 1\n";
  text += "add r0, c0, c1\nadd r1, c2, c3\nadd oPos, r0, r1\n";
  AssembleOptions options;
  options.validate = false;
  AssembleResult assembled = AssembleSource(text, "defs.vsh", options);
  ASSERT_TRUE(assembled.program) << assembled.diagnostics.ToString();
  const std::vector<int> registers = {0};
  VertexArrays inputs = MakeInputArrays(3, registers);
  VertexArrays outputs = MakeOutputArrays(3, *assembled.program);
  ASSERT_EQ(MakeEngine("ref", *assembled.program, ConstantBank()).value()->Run(inputs, outputs).message(), "");
  for (std::size_t vertex = 0; vertex < 3; ++vertex) {
    EXPECT_EQ(outputs.lane(static_cast<int>(OutputSlot::kPosition), 0)[vertex], 4092.0f + 4093 + 4094 + 4095);
    EXPECT_EQ(outputs.lane(static_cast<int>(OutputSlot::kPosition), 3)[vertex], 4.0f);
  }
}

}  // namespace
}  // namespace vs11
