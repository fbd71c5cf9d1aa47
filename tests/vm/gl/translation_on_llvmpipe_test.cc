// The translation run by a real driver: Mesa's llvmpipe (EGL surfaceless, OpenGL ES 3.0, transform
// feedback; vm/gl/gl_runner.h) against the reference engine, on every program of programs/. Each
// program's differences are printed with the first one, so a run shows what llvmpipe computes
// differently (README, "vs11 translate").
#include <algorithm>
#include <bit>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "tests/vm/engines/random_program.h"
#include "tests/vm/gl/gl_test_cases.h"
#include "vm/asm/assembler.h"
#include "vm/engines/reference_engine.h"
#include "vm/gl/gl_runner.h"
#include "vm/reference/verify.h"
#include "vm/translate/translate.h"

namespace vs11 {
namespace {

namespace fs = std::filesystem;
using random_program::Bits;

// The outputs captured, in the translation's names; oFog and oPts are one float each.
struct Captured {
  int slot;
  const char* name;
  int lanes;
};
constexpr Captured kCaptured[] = {
    {static_cast<int>(OutputSlot::kPosition), "vs11_oPos", 4}, {static_cast<int>(OutputSlot::kDiffuse), "oD0", 4},
    {static_cast<int>(OutputSlot::kSpecular), "oD1", 4},       {static_cast<int>(OutputSlot::kTexCoord0), "oT0", 4},
    {static_cast<int>(OutputSlot::kTexCoord0) + 1, "oT1", 4},  {static_cast<int>(OutputSlot::kTexCoord0) + 2, "oT2", 4},
    {static_cast<int>(OutputSlot::kTexCoord0) + 3, "oT3", 4},  {static_cast<int>(OutputSlot::kTexCoord0) + 4, "oT4", 4},
    {static_cast<int>(OutputSlot::kTexCoord0) + 5, "oT5", 4},  {static_cast<int>(OutputSlot::kTexCoord0) + 6, "oT6", 4},
    {static_cast<int>(OutputSlot::kTexCoord0) + 7, "oT7", 4},  {static_cast<int>(OutputSlot::kFog), "oFog", 1},
    {static_cast<int>(OutputSlot::kPointSize), "oPts", 1},
};

bool ContextReady() {
  static const bool ready = [] {
    const Result<std::string> renderer = gl::CreateLlvmpipeContext(std::nullopt);
    EXPECT_TRUE(renderer.ok()) << "no llvmpipe context: " << renderer.message();
    if (renderer) std::printf("[ gl ] renderer: %s\n", renderer->c_str());
    return renderer.ok();
  }();
  return ready;
}

struct Outcome {
  std::string error;         // the GL run failed
  int lanes = 0;             // compared
  int differing = 0;         // not bit-identical (NaN against NaN counts as equal)
  double worst_relative = 0;  // the largest difference over its output's scale (vs11 verify's measure)
  std::string first;         // the first difference, described
};

// Runs `program` on llvmpipe and on the reference engine, both under `rules`, and compares every
// captured lane. An
// output's scale is its largest |value| over the vertices and lanes (1 when all are 0), as in
// vs11 verify; a NaN on one side only is an infinite relative difference.
Outcome RunOnLlvmpipe(const Program& program, const ConstantBank& bank, const VertexArrays& inputs,
                      FloatRules rules = FloatRules::kD3d9) {
  Outcome outcome;
  translate::TranslateOptions options;
  options.float_rules = rules;
  options.target = translate::Target::kGlslEs300;  // the context gl_runner creates
  options.clip = translate::ClipSpace::kD3d;
  const std::string glsl = translate::TranslateToGlsl(program, options);
  std::vector<gl::GlAttribute> attributes;
  for (int reg : inputs.registers()) {
    gl::GlAttribute attribute;
    attribute.location = reg;
    for (std::size_t i = 0; i < inputs.count(); ++i) {
      for (int c = 0; c < 4; ++c) attribute.data.push_back(inputs.lane(reg, c)[i]);
    }
    attributes.push_back(std::move(attribute));
  }
  std::vector<float> constants;
  for (const Vec4f& row : bank.values()) constants.insert(constants.end(), row.begin(), row.end());
  std::vector<std::string> varyings;
  int floats = 0;
  for (const Captured& captured : kCaptured) {
    varyings.push_back(captured.name);
    floats += captured.lanes;
  }
  Result<std::unique_ptr<gl::TransformFeedbackRun>> run =
      gl::TransformFeedbackRun::Create(glsl, varyings, floats, attributes, constants);
  if (!run) {
    outcome.error = run.message();
    return outcome;
  }
  const Result<std::vector<float>> got = (*run)->DrawAndRead();
  if (!got) {
    outcome.error = got.message();
    return outcome;
  }

  VertexArrays expected = MakeOutputArrays(inputs.count(), program);
  EXPECT_EQ(MakeReferenceEngine(program, bank, rules)->Run(inputs, expected).message(), "");
  auto want_at = [&](const Captured& captured, int c, std::size_t vertex) {
    return expected.has(captured.slot) ? expected.lane(captured.slot, c)[vertex] : UnwrittenOutputValue(captured.slot)[c];
  };
  int offset = 0;
  for (const Captured& captured : kCaptured) {
    double scale = 0;
    for (std::size_t vertex = 0; vertex < inputs.count(); ++vertex) {
      for (int c = 0; c < captured.lanes; ++c) {
        const double want = want_at(captured, c, vertex);
        if (std::isfinite(want)) scale = std::max(scale, std::fabs(want));
      }
    }
    if (scale == 0) scale = 1;
    for (std::size_t vertex = 0; vertex < inputs.count(); ++vertex) {
      for (int c = 0; c < captured.lanes; ++c) {
        const float want = want_at(captured, c, vertex);
        const float have = (*got)[vertex * static_cast<std::size_t>(floats) + static_cast<std::size_t>(offset + c)];
        ++outcome.lanes;
        if (Bits(want) == Bits(have) || (std::isnan(want) && std::isnan(have))) continue;
        const double relative = std::isfinite(want) && std::isfinite(have) ? std::fabs(double{have} - want) / scale
                                                                           : INFINITY;
        outcome.worst_relative = std::max(outcome.worst_relative, relative);
        if (outcome.differing++ == 0) {
          outcome.first = fmt::format("{}.{} of vertex {}: llvmpipe {} (0x{:08X}), reference {} (0x{:08X})", captured.name,
                                      kLaneLetters[c], vertex, have, Bits(have), want, Bits(want));
        }
      }
    }
    offset += captured.lanes;
  }
  return outcome;
}

using gl_test::Opcodes;
using gl_test::OrdinaryConstants;
using gl_test::OrdinaryInputs;

// Every program of programs/ on llvmpipe. With ordinary inputs every lane is the reference engine's,
// bit for bit (the assertion); with the differential tests' special values (denormals, infinities,
// NaN payloads, signed zeros) the differences are printed, not asserted: llvmpipe flushes denormals,
// and GLSL ES 3.00 has no `precise` to stop Mesa's rewrites that assume no NaN, no signed zero and
// reassociable sums (README, "vs11 translate").
TEST(TranslationOnLlvmpipe, EveryProgramOfProgramsAgreesWithTheReferenceEngine) {
  ASSERT_TRUE(ContextReady());
  std::mt19937 rng(2026);
  random_program::ProgramGenerator special(99);
  int programs = 0, exact = 0;
  for (const fs::directory_entry& entry : fs::directory_iterator(fs::path(VS11_SOURCE_DIR) / "programs")) {
    if (entry.path().extension() != ".vsh") continue;
    const vs11::ProgramForVerify loaded = vs11::LoadProgramForVerify(entry.path());
    ASSERT_TRUE(loaded.program) << entry.path();
    const std::string name = entry.path().filename().string();
    // Inputs first: the values GCC drew when both were arguments of one call (evaluated right to
    // left); other draws can make fog.vsh write a denormal, which llvmpipe flushes.
    const VertexArrays inputs = OrdinaryInputs(256, rng);
    const ConstantBank constants = OrdinaryConstants(rng);
    const Outcome ordinary = RunOnLlvmpipe(*loaded.program, constants, inputs);
    ASSERT_EQ(ordinary.error, "") << name;
    EXPECT_EQ(ordinary.differing, 0) << name << " (" << Opcodes(*loaded.program) << "): " << ordinary.first;
    const Outcome legacy = RunOnLlvmpipe(*loaded.program, constants, inputs, FloatRules::kLegacy);
    ASSERT_EQ(legacy.error, "") << name;
    EXPECT_EQ(legacy.differing, 0) << name << " under legacy (" << Opcodes(*loaded.program) << "): " << legacy.first;
    const Outcome specials = RunOnLlvmpipe(*loaded.program, special.Constants(), special.Inputs(256));
    ASSERT_EQ(specials.error, "") << name;
    ++programs;
    exact += ordinary.differing == 0;
    std::printf("[ gl ] %s: ordinary inputs %d of %d lanes differ (worst %.2g of scale), %d under legacy; special "
                "values %d differ%s%s\n",
                name.c_str(), ordinary.differing, ordinary.lanes, ordinary.worst_relative, legacy.differing, specials.differing,
                specials.first.empty() ? "" : ", first: ", specials.first.c_str());
  }
  EXPECT_GE(programs, 10) << "programs/ lost its programs";
  std::printf("[ gl ] %d programs of programs/ on llvmpipe; %d bit-exact on ordinary inputs\n", programs, exact);
}

// An infinite constant times a zero lane in every instruction that multiplies, on llvmpipe: NaN
// under d3d9, 0 under legacy, the reference engine's bits under each (its values are pinned on
// every CPU engine by tests/vm/engines/float_rules_test.cc).
TEST(TranslationOnLlvmpipe, InfinityTimesZeroFollowsTheFloatRules) {
  ASSERT_TRUE(ContextReady());
  const gl_test::InfinityTimesZero test = gl_test::MakeInfinityTimesZero();
  ASSERT_TRUE(test.assembled.program) << test.assembled.diagnostics.ToString();
  const Program& program = *test.assembled.program;
  const ConstantBank& bank = test.bank;
  const VertexArrays& inputs = test.inputs;
  for (FloatRules rules : kAllFloatRules) {
    VertexArrays expected = MakeOutputArrays(1, program);
    ASSERT_EQ(MakeReferenceEngine(program, bank, rules)->Run(inputs, expected).message(), "");
    const float mul_x = expected.lane(static_cast<int>(OutputSlot::kDiffuse), 0)[0];
    EXPECT_EQ(std::isnan(mul_x), rules == FloatRules::kD3d9) << "the reference engine: " << mul_x;
    const Outcome outcome = RunOnLlvmpipe(program, bank, inputs, rules);
    ASSERT_EQ(outcome.error, "");
    EXPECT_EQ(outcome.differing, 0) << kFloatRulesNames.Name(rules) << ": " << outcome.first;
  }
}

// mul of every pair of zeros of both signs, infinities, NaN and ordinary numbers on llvmpipe, under
// each rule: the reference engine's bits, the sign of every zero included. (Denormals are left out:
// llvmpipe flushes them, README "vs11 translate".)
TEST(TranslationOnLlvmpipe, ZeroProductsKeepTheReferenceSigns) {
  ASSERT_TRUE(ContextReady());
  AssembleOptions assemble;
  assemble.require_position = false;
  // (c0 read too: the runner binds a constant bank, which a program must declare.)
  const AssembleResult assembled = AssembleSource("vs.1.1\nmov r0, v1\nmul oD0, v0, r0\nmov oD1, c0\n", "mul.vsh", assemble);
  ASSERT_TRUE(assembled.program) << assembled.diagnostics.ToString();
  const float values[] = {0.0f, -0.0f, 1.0f, -2.5f, INFINITY, -INFINITY, std::bit_cast<float>(0x7FC00000u), FLT_MAX};
  const VertexArrays inputs = random_program::EveryPairOf(values);
  for (FloatRules rules : kAllFloatRules) {
    const Outcome outcome = RunOnLlvmpipe(*assembled.program, ConstantBank(), inputs, rules);
    ASSERT_EQ(outcome.error, "");
    EXPECT_EQ(outcome.differing, 0) << kFloatRulesNames.Name(rules) << ": " << outcome.first;
  }
}

}  // namespace
}  // namespace vs11
