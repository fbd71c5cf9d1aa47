// The gl engine (vm/gl/gl_engine.h) on Mesa's llvmpipe against the reference engine, on both of its
// paths (the compute shader and transform feedback: every test runs once per GlPath): every program of
// programs/ and generated programs of the differential tests' generator, on ordinary inputs (floats in
// [-4, 4]), bit for bit; calls larger than one draw, constants changed between runs, and the factory's
// registration. The tools' side (errors without EGL, --gl-device) is in gl_engine_cli_test.cc. These
// tests run in ctest's vs11_tests.llvmpipe entry, which CI's sanitizer stage leaves out.
#include "vm/gl/gl_engine.h"

#include <EGL/egl.h>

#include <bit>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <optional>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "tests/vm/engines/later_model_comparison.h"
#include "tests/vm/engines/random_program.h"
#include "tests/vm/gl/gl_test_cases.h"
#include "vm/asm/assembler.h"
#include "vm/core/float_rules.h"
#include "vm/engines/engine_factory.h"
#include "vm/reference/verify.h"
#include "vm/translate/translate.h"

namespace vs11 {
namespace {

namespace fs = std::filesystem;
using random_program::Bits;

class GlEngineTest : public ::testing::TestWithParam<gl::GlPath> {
 protected:
  void SetUp() override { gl::RegisterGlEngine(); }
};

// The gl engine's options on the path under test, and a check that the engine took it.
EngineOptions OnPath(gl::GlPath path, FloatRules rules = FloatRules::kD3d9) {
  EngineOptions options{.float_rules = rules};
  gl::GlOptions gl_options;
  gl_options.path = path;
  options.settings.Set(gl_options);
  return options;
}

// The gl engine on the options' path, or null after a test failure that says why it could not be built.
std::unique_ptr<Engine> MakeGl(const Program& program, const ConstantBank& bank, const EngineOptions& options) {
  Result<std::unique_ptr<Engine>> made = MakeEngine("gl", program, bank, options);
  EXPECT_TRUE(made.ok()) << made.message();
  if (!made) return nullptr;
  std::unique_ptr<Engine> gl = std::move(made).value();
  if (Info(program.model()).runs) {  // (a later model's engine wraps one gl engine per specialisation)
    EXPECT_EQ(gl::GlPathOf(*gl), options.settings.Get<gl::GlOptions>().path);
  }
  return gl;
}

using gl_test::Opcodes;
using gl_test::Ordinary;
using gl_test::OrdinaryConstants;
using gl_test::OrdinaryInputs;

// How the gl engine's outputs compare with the reference engine's, over every lane the translation's
// interface carries of every output register the program writes (all four lanes, oFog's and oPts' too).
struct Comparison {
  std::string error;  // the gl engine's
  int lanes = 0;
  int flushed = 0;    // the reference's value is a denormal and the gl engine's a zero: llvmpipe flushes
  int differing = 0;  // any other difference of bits (any NaN equals any NaN: GLSL keeps no payloads)
  std::string first;  // the first such difference, described
};

bool IsDenormal(float x) { return std::fpclassify(x) == FP_SUBNORMAL; }

Comparison CompareWithReference(gl::GlPath path, const Program& program, const ConstantBank& bank,
                                const VertexArrays& inputs, FloatRules rules = FloatRules::kD3d9) {
  Comparison comparison;
  VertexArrays expected = MakeOutputArrays(inputs.count(), program);
  VertexArrays actual = MakeOutputArrays(inputs.count(), program);
  const EngineOptions options = OnPath(path, rules);
  EXPECT_EQ(MakeEngine("ref", program, bank, options).value()->Run(inputs, expected).message(), "");
  std::unique_ptr<Engine> gl = MakeGl(program, bank, options);
  if (gl == nullptr) {
    comparison.error = "the gl engine could not be built";
    return comparison;
  }
  comparison.error = gl->Run(inputs, actual).message();
  if (!comparison.error.empty()) return comparison;
  for (int slot : expected.registers()) {
    const int lanes = translate::OutputVariableOf(slot, /*exact_on_driver=*/true).components;
    for (int c = 0; c < lanes; ++c) {
      for (std::size_t v = 0; v < inputs.count(); ++v) {
        const float want = expected.lane(slot, c)[v], have = actual.lane(slot, c)[v];
        ++comparison.lanes;
        if (Bits(want) == Bits(have) || (std::isnan(want) && std::isnan(have))) continue;
        if (IsDenormal(want) && have == 0.0f) {
          ++comparison.flushed;
          continue;
        }
        if (comparison.differing++ == 0) {
          comparison.first = fmt::format("{}.{} of vertex {}: gl {} (0x{:08X}), ref {} (0x{:08X})", OutputSlotName(slot),
                                         kLaneLetters[c], v, have, Bits(have), want, Bits(want));
        }
      }
    }
  }
  return comparison;
}

// Ordinary inputs and constants can still make a denormal (fog's exp of a large negative number):
// llvmpipe flushes it to zero, and such lanes are printed; every other lane holds the reference's bits.
TEST_P(GlEngineTest, EveryProgramOfProgramsGivesTheReferenceBitsOnOrdinaryInputs) {
  std::mt19937 rng(20);
  int programs = 0;
  for (const fs::directory_entry& entry : fs::directory_iterator(fs::path(VS11_SOURCE_DIR) / "programs")) {
    if (entry.path().extension() != ".vsh") continue;
    const vs11::ProgramForVerify loaded = vs11::LoadProgramForVerify(entry.path());
    ASSERT_TRUE(loaded.program) << entry.path();
    const Comparison comparison =
        CompareWithReference(GetParam(), *loaded.program, OrdinaryConstants(rng), OrdinaryInputs(128, rng));
    ASSERT_EQ(comparison.error, "") << entry.path();
    EXPECT_EQ(comparison.differing, 0) << entry.path().filename() << " (" << Opcodes(*loaded.program)
                                       << "): " << comparison.first;
    if (comparison.flushed > 0) {
      std::printf("[ gl ] %s: %d of %d lanes hold a denormal in the reference that llvmpipe flushed to zero\n",
                  entry.path().filename().c_str(), comparison.flushed, comparison.lanes);
    }
    ++programs;
  }
  EXPECT_GE(programs, 10) << "programs/ lost its programs";
}

// Later models' programs run as their specialisation for i#/b# (vm/engines/static_flow_engine.h), dynamic
// flow as execution masks, translated like any vs_1_1 program: a skinning loop over bones through c[aL],
// nested rep/if b#/break, calls, a per-vertex if_comp and break_comp in a loop with predicated writes, the
// later arithmetic rows with _sat, _abs, a0.y and r20, and vs_3_0's outputs by declaration with o[aL]; then
// new integer constants, a second specialisation.
TEST_P(GlEngineTest, LaterModelProgramsGiveTheReferenceBits) {
  const char* const kPrograms[] = {
      ("vs_2_0\ndcl_position v0\nmov r0, c0\nloop aL, i0\ndp4 r1.x, v0, c0[aL]\n"
       "dp4 r1.y, v0, c1[aL]\ndp4 r1.z, v0, c2[aL]\ndp4 r1.w, v0, c3[aL]\nmad r0, r1, c30[aL].x, r0\nendloop\n"
       "mov oPos, r0\n"),
      ("vs_2_x\ndefb b0, true\ndefb b1, false\ndcl_position v0\ndcl_normal v1\n"
       "mov r0, v0\nmov r1, v1\nrep i1\nif b0\nmad r0, r0, c3, r1\nelse\nadd r0, r0, c4\nendif\nrep i1\n"
       "mul r1, r1, c5\nif !b1\nbreak\nendif\nendrep\ncall l0\nendrep\ncallnz l0, b1\nmov oPos, r0\n"
       "mov oD0, r1\nret\nlabel l0\nmax r0, r0, -r1\nret\n"),
      ("vs_2_x\ndcl_position v0\ndcl_normal v1\nmov r0, v0\nmov r1, v1\nrep i1\nif_gt r0.x, c0.x\n"
       "add r0, r0, c1\nelse\nmul r0, r0, c2\nendif\nbreak_lt r0.y, c3.x\nendrep\nsetp_lt p0, v0, c1\n"
       "(p0) mov r0.yz, c1.w\n(!p0.x) add r1, r1, c4\nmov oPos, r0\nmov oD0, r1\n"),
      ("vs_3_0\ndcl_position v0\ndcl_normal v1\ndcl_position o0\ndcl_texcoord0 o1\ndcl_texcoord1 o2\n"
       "dcl_texcoord2 o3\nmov r20, v1\nnrm r1, r20\ncrs r2.xyz, v0, r1\nmov r2.w, c5.x\n"
       "pow_sat r3, r20_abs.x, c6.y\nsincos r4.xy, v0.z\nmov r4.zw, c7\nlrp r5, c8, r2, r4\n"
       "sgn r6, -r5, r7, r8\nmova a0.yw, c9\nmov r9, c[a0.y + 10]\nabs r10, -r9\nmov o0, v0\nmov o1, r5\n"
       "mov o2, r6\nadd o3, r3, r10\n"),
      ("vs_3_0\ndcl_position v0\ndcl_position o0\ndcl_texcoord0 o1\n"
       "dcl_texcoord1 o2\nmov o0, v0\nloop aL, i2\nmul o[aL], v0, c[aL + 7]\nendloop\n"),
  };
  std::mt19937 rng(33);
  for (const char* source : kPrograms) {
    const Program program = later_model::Assemble(source);
    ASSERT_FALSE(program.instructions.empty()) << source;
    ConstantBank bank = OrdinaryConstants(rng);
    bank.integer(0) = {3, 10, 4, 0};
    bank.integer(1) = {4, 0, 0, 0};
    bank.integer(2) = {2, 1, 1, 0};
    const VertexArrays inputs = OrdinaryInputs(40, rng);
    for (FloatRules rules : kAllFloatRules) {
      const Comparison comparison = CompareWithReference(GetParam(), program, bank, inputs, rules);
      ASSERT_EQ(comparison.error, "") << source;
      EXPECT_EQ(comparison.differing, 0) << source << comparison.first;
    }
    // Other loop counts from the API: a second specialisation.
    bank.integer(0) = {2, 12, 4, 0};
    bank.integer(1) = {2, 0, 0, 0};
    bank.integer(2) = {1, 2, 1, 0};
    const Comparison again = CompareWithReference(GetParam(), program, bank, inputs);
    ASSERT_EQ(again.error, "") << source;
    EXPECT_EQ(again.differing, 0) << source << again.first;
    EXPECT_EQ(again.flushed, 0) << source;
  }
}

// A generated program with its def literals made ordinary too (the generator mixes special values in).
Program OrdinaryGeneratedProgram(random_program::ProgramGenerator& generator, std::mt19937& rng) {
  Program program = generator.MakeProgram();
  for (Instruction& instruction : program.instructions) {
    if (instruction.opcode != Opcode::kDef) continue;
    for (std::uint32_t& bits : instruction.def_bits) bits = Bits(Ordinary(rng));
  }
  return program;
}

int GeneratedProgramCount() {
  const char* text = std::getenv("VS11_GL_PROGRAMS");
  return text != nullptr ? std::atoi(text) : 300;
}

// The differential tests' generator, 300 programs (VS11_GL_PROGRAMS overrides the count) of up to
// 24 random instructions after the temporaries' set-up, on ordinary inputs, constants and def
// literals. Ordinary inputs can still make a denormal (expp of -130, a product of two small numbers),
// which llvmpipe flushes to zero: such lanes are counted and printed, every other lane must hold the
// reference's bits. About 12 s of CPU (llvmpipe compiling 300 shaders), 35-50 s of wall time at load 18.
TEST_P(GlEngineTest, GeneratedProgramsGiveTheReferenceBitsOnOrdinaryInputs) {
  random_program::ProgramGenerator generator(2020);
  std::mt19937 rng(21);
  int exact = 0, flushed_lanes = 0;
  const int count = GeneratedProgramCount();
  for (int n = 0; n < count; ++n) {
    const Program program = OrdinaryGeneratedProgram(generator, rng);
    const Comparison comparison = CompareWithReference(GetParam(), program, OrdinaryConstants(rng), OrdinaryInputs(16, rng));
    ASSERT_EQ(comparison.error, "") << "program " << n;
    EXPECT_EQ(comparison.differing, 0) << "program " << n << " (" << Opcodes(program) << "): " << comparison.first;
    exact += comparison.differing == 0 && comparison.flushed == 0;
    flushed_lanes += comparison.flushed;
  }
  std::printf("[ gl ] %d of %d generated programs bit-exact in every lane; %d lanes where the reference holds a "
              "denormal that llvmpipe flushed to zero\n", exact, count, flushed_lanes);
  EXPECT_GT(exact, count * 9 / 10);
}

// A value's kind, for the special-value account below.
std::string KindOf(float x) {
  if (std::isnan(x)) return "NaN";
  if (std::isinf(x)) return x > 0 ? "+inf" : "-inf";
  if (x == 0.0f) return std::signbit(x) ? "-0" : "+0";
  if (IsDenormal(x)) return "denormal";
  if (std::fabs(x) == FLT_MAX) return "FLT_MAX";
  return "finite";
}

// `value` with a denormal replaced by a zero of its sign.
float WithoutDenormal(float value) { return IsDenormal(value) ? std::copysign(0.0f, value) : value; }

// Counts of differing lanes by (reference kind -> gl kind), over 16 vertices of special values.
void CountKinds(gl::GlPath path, const Program& program, const ConstantBank& bank, const VertexArrays& inputs,
                std::map<std::string, int>& kinds, int& exact_programs) {
  VertexArrays expected = MakeOutputArrays(inputs.count(), program);
  VertexArrays actual = MakeOutputArrays(inputs.count(), program);
  ASSERT_EQ(MakeEngine("ref", program, bank).value()->Run(inputs, expected).message(), "");
  std::unique_ptr<Engine> gl = MakeGl(program, bank, OnPath(path));
  ASSERT_NE(gl, nullptr);
  ASSERT_EQ(gl->Run(inputs, actual).message(), "");
  bool exact = true;
  for (int slot : expected.registers()) {
    for (int c = 0; c < translate::OutputVariableOf(slot, /*exact_on_driver=*/true).components; ++c) {
      for (std::size_t v = 0; v < inputs.count(); ++v) {
        const float want = expected.lane(slot, c)[v], have = actual.lane(slot, c)[v];
        if (Bits(want) == Bits(have) || (std::isnan(want) && std::isnan(have))) continue;
        ++kinds[KindOf(want) + " -> " + KindOf(have)];
        exact = false;
      }
    }
  }
  exact_programs += exact;
}

// The differential tests' special values (signed zeros, denormals, infinities, NaN payloads, FLT_MAX,
// random bit patterns) on 50 generated programs, as they are and with every denormal in the inputs,
// constants and defs replaced by a zero: llvmpipe flushes denormals (README, "--engine gl"), and
// without them in the inputs at least 45 of the 50 programs give the reference's bits. The differing
// lanes are printed by kind. About 5 s of CPU with Mesa's shader cache cold.
TEST_P(GlEngineTest, SpecialValuesDifferWhereLlvmpipeFlushesDenormals) {
  for (bool denormals : {true, false}) {
    random_program::ProgramGenerator generator(2020);
    random_program::ProgramGenerator values(99);
    std::map<std::string, int> kinds;
    int exact = 0;
    constexpr int kPrograms = 50;
    for (int n = 0; n < kPrograms; ++n) {
      Program program = generator.MakeProgram();
      ConstantBank bank = values.Constants();
      VertexArrays inputs = values.Inputs(16);
      if (!denormals) {
        for (Instruction& instruction : program.instructions) {
          for (std::uint32_t& bits : instruction.def_bits) bits = Bits(WithoutDenormal(std::bit_cast<float>(bits)));
        }
        for (int reg = 0; reg < bank.size(); ++reg) {
          for (float& value : bank[reg]) value = WithoutDenormal(value);
        }
        for (int reg : random_program::kInputs) {
          for (int c = 0; c < 4; ++c) {
            if (const std::optional<float> uniform = inputs.uniform(reg, c)) {
              inputs.FillUniform(reg, c, WithoutDenormal(*uniform));
              continue;
            }
            for (std::size_t v = 0; v < inputs.count(); ++v) inputs.lane(reg, c)[v] = WithoutDenormal(inputs.lane(reg, c)[v]);
          }
        }
      }
      CountKinds(GetParam(), program, bank, inputs, kinds, exact);
    }
    std::printf("[ gl ] special values%s: %d of %d generated programs bit-exact; differing lanes by kind "
                "(reference -> gl):\n", denormals ? "" : " without denormals", exact, kPrograms);
    for (const auto& [kind, lanes] : kinds) std::printf("[ gl ]   %5d  %s\n", lanes, kind.c_str());
    if (!denormals) {
      EXPECT_GE(exact, 45);
    }
  }
}

Program ProgramFromFile(const char* name) {
  vs11::ProgramForVerify loaded =
      vs11::LoadProgramForVerify(fs::path(VS11_SOURCE_DIR) / "programs" / name);
  EXPECT_TRUE(loaded.program) << name;
  return loaded.program ? std::move(*loaded.program) : Program();
}

// More vertices than one draw takes (65536): the call is split, every vertex lands in its place.
// --float-rules through the gl engine: an infinite constant times a zero lane in every instruction
// that multiplies gives NaN under d3d9 and 0 under legacy, the reference engine's bits under each
// (tests/vm/engines/float_rules_test.cc pins those bits on every CPU engine).
TEST_P(GlEngineTest, InfinityTimesZeroFollowsTheEnginesFloatRules) {
  const gl_test::InfinityTimesZero test = gl_test::MakeInfinityTimesZero();
  ASSERT_TRUE(test.assembled.program) << test.assembled.diagnostics.ToString();
  const Program& program = *test.assembled.program;
  const ConstantBank& bank = test.bank;
  const VertexArrays& inputs = test.inputs;
  for (FloatRules rules : kAllFloatRules) {
    VertexArrays outputs = MakeOutputArrays(1, program);
    std::unique_ptr<Engine> gl = MakeGl(program, bank, OnPath(GetParam(), rules));
    ASSERT_NE(gl, nullptr);
    ASSERT_EQ(gl->Run(inputs, outputs).message(), "");
    const float mul_x = outputs.lane(static_cast<int>(OutputSlot::kDiffuse), 0)[0];
    if (rules == FloatRules::kD3d9) {
      EXPECT_TRUE(std::isnan(mul_x)) << "d3d9: inf * 0 gave " << mul_x;
    } else {
      EXPECT_EQ(Bits(mul_x), 0u) << "legacy: inf * 0 gave " << mul_x;
    }
    const Comparison comparison = CompareWithReference(GetParam(), program, bank, inputs, rules);
    EXPECT_EQ(comparison.differing, 0) << kFloatRulesNames.Name(rules) << ": " << comparison.first;
    EXPECT_EQ(comparison.flushed, 0);
  }
}

TEST_P(GlEngineTest, ACallLargerThanOneDrawGivesEveryVertexItsOutputs) {
  std::mt19937 rng(22);
  const Comparison comparison =
      CompareWithReference(GetParam(), ProgramFromFile("skinning.vsh"), OrdinaryConstants(rng), OrdinaryInputs(65536 + 4099, rng));
  ASSERT_EQ(comparison.error, "");
  EXPECT_EQ(comparison.lanes, (65536 + 4099) * 8);  // oPos and oD0
  EXPECT_EQ(comparison.differing + comparison.flushed, 0) << comparison.first;
}

// One engine, runs with different banks in between, as irrmap's levels do; a bank of another size
// rebuilds the translation (its c[N] and the relative-read range).
TEST_P(GlEngineTest, SetConstantsBetweenRunsGivesEachBanksOutputs) {
  std::mt19937 rng(23);
  const Program program = ProgramFromFile("all_instructions.vsh");
  const VertexArrays inputs = OrdinaryInputs(64, rng);
  std::unique_ptr<Engine> gl = MakeGl(program, OrdinaryConstants(rng), OnPath(GetParam()));
  ASSERT_NE(gl, nullptr);
  for (int bank_size : {kDefaultConstantCount, kDefaultConstantCount, 192}) {
    ConstantBank bank(bank_size);
    for (int reg = 0; reg < bank.size(); ++reg) {
      for (int c = 0; c < 4; ++c) bank[reg][c] = Ordinary(rng);
    }
    ASSERT_EQ(gl->SetConstants(bank).message(), "");
    VertexArrays actual = MakeOutputArrays(inputs.count(), program);
    VertexArrays expected = MakeOutputArrays(inputs.count(), program);
    ASSERT_EQ(gl->Run(inputs, actual).message(), "");
    ASSERT_EQ(MakeEngine("ref", program, bank).value()->Run(inputs, expected).message(), "");
    for (int slot : expected.registers()) {
      for (int c = 0; c < translate::OutputVariableOf(slot, /*exact_on_driver=*/true).components; ++c) {
        for (std::size_t v = 0; v < inputs.count(); ++v) {
          ASSERT_EQ(Bits(actual.lane(slot, c)[v]), Bits(expected.lane(slot, c)[v]))
              << "bank of " << bank_size << ", " << OutputSlotName(slot) << "." << kLaneLetters[c] << " of vertex " << v;
        }
      }
    }
  }
}

// A bank larger than the driver holds (skinning.vsh reads c[a0.x + k], so the whole bank is live)
// fails SetConstants with the link's code and the bank's size; the engine stays failed: every later
// call returns that error, and Run writes NaN.
TEST_P(GlEngineTest, ABankTheDriverCannotHoldFailsSetConstantsAndEveryLaterCall) {
  std::mt19937 rng(25);
  const Program program = ProgramFromFile("skinning.vsh");
  const ConstantBank bank = OrdinaryConstants(rng);
  const VertexArrays inputs = OrdinaryInputs(8, rng);
  std::unique_ptr<Engine> gl = MakeGl(program, bank, OnPath(GetParam()));
  ASSERT_NE(gl, nullptr);
  VertexArrays outputs = MakeOutputArrays(inputs.count(), program);
  ASSERT_EQ(gl->Run(inputs, outputs).message(), "");
  const Status set = gl->SetConstants(ConstantBank(1 << 16));
  ASSERT_FALSE(set.ok()) << "a bank of 65536 registers fitted";
  EXPECT_EQ(set.error().code, DiagnosticCode::kGlCompile);
  EXPECT_NE(set.message().find("the constant bank is c[65536]"), std::string::npos) << set.message();
  const Status ran = gl->Run(inputs, outputs);
  ASSERT_FALSE(ran.ok());
  EXPECT_EQ(ran.error().code, DiagnosticCode::kGlCompile);
  EXPECT_EQ(ran.message(), set.message());
  for (int slot : outputs.registers()) {
    for (int c = 0; c < 4; ++c) {
      for (std::size_t v = 0; v < inputs.count(); ++v) {
        ASSERT_TRUE(std::isnan(outputs.lane(slot, c)[v])) << OutputSlotName(slot) << " of vertex " << v;
      }
    }
  }
  EXPECT_EQ(gl->SetConstants(bank).message(), set.message());
  EXPECT_EQ(gl->Run(inputs, outputs).message(), set.message());
}

// An engine is made on one thread and runs on others (vm/core/machine.h allows it when the calls are
// ordered); and it leaves the calling thread's current EGL context as it found it.
TEST_P(GlEngineTest, RunsWhereverItIsCalledAndLeavesTheCurrentContextAlone) {
  std::mt19937 rng(24);
  const Program program = ProgramFromFile("point_light.vsh");
  const ConstantBank bank = OrdinaryConstants(rng);
  const VertexArrays inputs = OrdinaryInputs(100, rng);
  VertexArrays expected = MakeOutputArrays(inputs.count(), program);
  ASSERT_EQ(MakeEngine("ref", program, bank).value()->Run(inputs, expected).message(), "");
  const void* current_before = eglGetCurrentContext();
  std::unique_ptr<Engine> gl = MakeGl(program, bank, OnPath(GetParam()));
  ASSERT_NE(gl, nullptr);
  EXPECT_EQ(eglGetCurrentContext(), current_before);
  for (int round = 0; round < 3; ++round) {
    VertexArrays actual = MakeOutputArrays(inputs.count(), program);
    Status ran;
    std::thread([&] { ran = gl->Run(inputs, actual); }).join();
    ASSERT_EQ(ran.message(), "") << "round " << round;
    for (int slot : expected.registers()) {
      for (std::size_t v = 0; v < inputs.count(); ++v) {
        ASSERT_EQ(Bits(actual.lane(slot, 0)[v]), Bits(expected.lane(slot, 0)[v])) << "round " << round;
      }
    }
  }
  VertexArrays here = MakeOutputArrays(inputs.count(), program);
  ASSERT_EQ(gl->Run(inputs, here).message(), "");
  EXPECT_EQ(eglGetCurrentContext(), current_before);
}

// Without a registered maker (a program that does not link vm/gl, such as the Python module) the
// factory says so, with its code.
TEST(GlEngineFactoryTest, WithoutRegistrationTheFactoryGivesAnErrorThatSaysWhy) {
  gl::RegisterGlEngine();
  UnregisterEngine("gl");
  const Program program = ProgramFromFile("fog.vsh");
  const Result<std::unique_ptr<Engine>> engine = MakeEngine("gl", program, ConstantBank());
  gl::RegisterGlEngine();
  ASSERT_FALSE(engine.ok());
  EXPECT_EQ(engine.error().code, DiagnosticCode::kEngineUnavailable);
  EXPECT_NE(engine.message().find("the gl engine is not part of this program"), std::string::npos) << engine.message();
}

INSTANTIATE_TEST_SUITE_P(Paths, GlEngineTest, ::testing::Values(gl::GlPath::kCompute, gl::GlPath::kTransformFeedback),
                         [](const ::testing::TestParamInfo<gl::GlPath>& info) {
                           return info.param == gl::GlPath::kCompute ? std::string("Compute")
                                                                     : std::string("TransformFeedback");
                         });

}  // namespace
}  // namespace vs11
