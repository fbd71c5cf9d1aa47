// The batch engine on hand-written programs with expected values (../shared/spec/vs_1_1.md §3.3),
// run on every Highway target this build compiled and the CPU supports. Bit-for-bit agreement with
// the reference engine on everything else is tests/vm/engines/engine_differential_test.cc's job.
#include "vm/engines/batch_engine.h"

#include <bit>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "hwy/highway.h"
#include "hwy/tests/hwy_gtest.h"
#include "vm/asm/assembler.h"
#include "vm/core/thread_pool.h"

namespace vs11 {
namespace {

std::uint32_t Bits(float x) { return std::bit_cast<std::uint32_t>(x); }

Program Assemble(const std::string& body) {
  AssembleOptions options;
  options.validate = false;  // some probes read unwritten temporaries or alias on purpose
  AssembleResult assembled = AssembleSource("vs.1.1\n" + body, "probe.vsh", options);
  EXPECT_TRUE(assembled.program.has_value()) << assembled.diagnostics.ToString();
  return assembled.program.value_or(Program{});
}

ConstantBank Constants(std::initializer_list<std::pair<int, Vec4f>> values) {
  ConstantBank bank;
  for (const auto& [index, value] : values) bank[index] = value;
  return bank;
}

// Inputs v0..v2 for `count` vertices, vertex i of v# filled by `value(reg, i)`.
template <class Fill>
VertexArrays Inputs(std::size_t count, Fill value) {
  const int registers[] = {0, 1, 2};
  VertexArrays inputs = MakeInputArrays(count, registers);
  for (int reg : registers) {
    for (std::size_t i = 0; i < count; ++i) {
      const Vec4f v = value(reg, i);
      for (int c = 0; c < 4; ++c) inputs.lane(reg, c)[i] = v[c];
    }
  }
  return inputs;
}

Vec4f Lanes(const VertexArrays& arrays, int reg, std::size_t i) {
  return {arrays.lane(reg, 0)[i], arrays.lane(reg, 1)[i], arrays.lane(reg, 2)[i], arrays.lane(reg, 3)[i]};
}

void ExpectBitsEqual(const Vec4f& actual, const Vec4f& expected, const std::string& context) {
  for (int c = 0; c < 4; ++c) {
    EXPECT_EQ(Bits(actual[c]), Bits(expected[c]))
        << context << ", lane " << c << ": " << actual[c] << " vs expected " << expected[c];
  }
}

void ExpectSameBits(const VertexArrays& actual, const VertexArrays& expected, std::size_t count) {
  ASSERT_EQ(actual.registers(), expected.registers());
  for (int slot : expected.registers()) {
    for (int c = 0; c < 4; ++c) {
      for (std::size_t i = 0; i < count; ++i) {
        ASSERT_EQ(Bits(actual.lane(slot, c)[i]), Bits(expected.lane(slot, c)[i]))
            << OutputSlotName(slot) << " lane " << c << " vertex " << i;
      }
    }
  }
}

constexpr int kPosition = static_cast<int>(OutputSlot::kPosition);

// Runs `body` on one vertex (v0 = `v0`) and returns oPos.
Vec4f RunOnce(const std::string& body, const Vec4f& v0, const ConstantBank& constants) {
  const Program program = Assemble(body);
  VertexArrays inputs = Inputs(1, [&](int reg, std::size_t) { return reg == 0 ? v0 : kDefaultInput; });
  VertexArrays outputs = MakeOutputArrays(1, program);
  EXPECT_EQ(MakeBatchEngine(program, constants, {})->Run(inputs, outputs).message(), "");
  return Lanes(outputs, kPosition, 0);
}

class BatchEngine : public hwy::TestWithParamTarget {};

// The jit engine (machine code where the program compiles) or the batch engine's kernels.
std::unique_ptr<Engine> MakeBatchOrJit(bool compiled, const Program& program, const ConstantBank& constants,
                                       const EngineOptions& options) {
  return compiled ? MakeJitEngine(program, constants, options) : MakeBatchEngine(program, constants, options);
}
HWY_TARGET_INSTANTIATE_TEST_SUITE_P(BatchEngine);

struct InstructionCase {
  const char* body;
  Vec4f v0;
  Vec4f expected;  // oPos
};

const ConstantBank& CaseConstants() {
  static const ConstantBank bank = Constants({{0, {10, 20, 30, 40}},
                                              {1, {0.5f, 0.5f, 0.5f, 0.5f}},
                                              {2, {2, 2, 2, 2}},
                                              {3, {0, 1, -0.0f, 8}},
                                              // c4..c7: a matrix whose rows pick w, x, y, z.
                                              {4, {0, 0, 0, 1}},
                                              {5, {1, 0, 0, 0}},
                                              {6, {0, 1, 0, 0}},
                                              {7, {0, 0, 1, 0}}});
  return bank;
}

TEST_P(BatchEngine, ComputesEachInstruction) {
  constexpr float kMax = FLT_MAX;
  const Vec4f v = {1, 2, 3, 4};
  const InstructionCase cases[] = {
      {"mov oPos, v0", v, {1, 2, 3, 4}},
      {"mov oPos, -v0.wzyx", v, {-4, -3, -2, -1}},
      {"add oPos, v0, c0", v, {11, 22, 33, 44}},
      {"sub oPos, v0, c0.wzyx", v, {-39, -28, -17, -6}},
      {"mul oPos, v0, -c0.x", v, {-10, -20, -30, -40}},
      {"mad oPos, v0, c0.y, c1", v, {20.5f, 40.5f, 60.5f, 80.5f}},
      {"dp3 oPos, v0, c0", v, {140, 140, 140, 140}},
      {"dp4 oPos.yw, v0, c0", v, {0, 300, 0, 300}},
      {"min oPos, v0, c2", v, {1, 2, 2, 2}},
      {"max oPos, v0, c2", v, {2, 2, 3, 4}},
      {"slt oPos, v0, c2", v, {1, 0, 0, 0}},
      {"sge oPos, v0, c2", v, {0, 1, 1, 1}},
      {"frc oPos.xy, v0", {-0.25f, 2.75f, 0, 0}, {0.75f, 0.75f, 0, 0}},
      {"frc oPos.xy, -v0", {0.0f, 1.5f, 0, 0}, {0.0f, 0.5f, 0, 0}},  // -0 - floor(-0) = +0
      {"rcp oPos, v0", v, {0.25f, 0.25f, 0.25f, 0.25f}},  // scalar ops read the w lane
      {"rcp oPos, c3.z", v, {kMax, kMax, kMax, kMax}},     // rcp(-0) = +FLT_MAX
      {"rsq oPos, -v0.w", v, {0.5f, 0.5f, 0.5f, 0.5f}},
      {"rsq oPos.x, c3.x", v, {kMax, 0, 0, 0}},
      {"exp oPos, v0.y", v, {4, 4, 4, 4}},
      {"log oPos, v0.w", v, {2, 2, 2, 2}},
      {"log oPos.z, c3.x", v, {0, 0, -kMax, 0}},
      {"logp oPos.xyw, c3.w", v, {3, 1, 0, 1}},
      {"logp oPos, c3.x", v, {-kMax, 1, -kMax, 1}},
      {"expp oPos.xyw, v0.z", {0, 0, 2.5f, 0}, {4, 0.5f, 0, 1}},
      {"lit oPos, v0", {-1, 0.5f, 0, 2}, {1, 0, 0, 1}},
      {"lit oPos.xyw, v0", {0.5f, 0.5f, 0, 2}, {1, 0.5f, 0, 1}},
      {"dst oPos, v0, c0", v, {1, 40, 3, 40}},
      {"m4x4 oPos, v0, c4", v, {4, 1, 2, 3}},
      {"m4x3 oPos, v0, c4", v, {4, 1, 2, 0}},
      {"m3x4 oPos, v0, c4", v, {0, 1, 2, 3}},
      {"m3x3 oPos, v0, c5", v, {1, 2, 3, 0}},
      {"m3x2 oPos, v0, c5", v, {1, 2, 0, 0}},  // rows beyond the matrix are not written
      {"nop\nmov oPos.zw, v0", v, {0, 0, 3, 4}},
      // All sources are read before the masked store.
      {"mov r0, v0\nadd r0, r0.yzwx, r0\nmov oPos, r0", v, {3, 5, 7, 5}},
      {"mov r0, v0\nmov r0.xy, r0.yx\nmov oPos, r0", v, {2, 1, 3, 4}},
      {"mov r0, v0\nm4x4 r0, r0, c4\nmov oPos, r0", v, {4, 1, 2, 3}},
      // dp4s sharing a vector run as one step, unless one reads what an earlier one wrote.
      {"mov r0, v0\ndp4 r0.x, r0, c4\ndp4 r0.y, r0, c5\ndp4 r0.z, r0, c6\nmov oPos, r0", v, {4, 4, 4, 4}},
      {"dp4 r0.x, v0, c4\ndp4 r0.y, v0, c5\ndp4 r0.z, v0, c6\ndp4 r0.w, v0, c7\nmov oPos, r0", v, {4, 1, 2, 3}},
      // Temporaries start at 0, absent inputs read (0, 0, 0, 1).
      {"add oPos, -r7, v0", v, {1, 2, 3, 4}},
      {"add oPos, v3, v0", v, {1, 2, 3, 5}},
      // Relative constants: a0.x = floor(v0.x); outside the bank they read 0.
      {"mov a0.x, v0.x\nmov oPos, c[a0.x + 1]", {1.5f, 0, 0, 0}, {2, 2, 2, 2}},
      {"mov a0.x, v0.x\nmov oPos, c[a0.x + 1]", {-0.5f, 0, 0, 0}, {10, 20, 30, 40}},
      {"mov a0.x, v0.x\nmov oPos, c[a0.x + 1]", {-2, 0, 0, 0}, {0, 0, 0, 0}},
      {"mov a0.x, v0.x\nmov oPos, c[a0.x + 1]", {std::nanf(""), 0, 0, 0}, {0, 0, 0, 0}},
      {"mov a0.x, v0.x\nm4x4 oPos, v0.w, c[a0.x + 3]", {2, 0, 0, 1}, {1, 1, 1, 0}},  // rows c5..c8
  };
  for (const InstructionCase& test : cases) {
    ExpectBitsEqual(RunOnce(test.body, test.v0, CaseConstants()), test.expected, test.body);
  }
}

TEST_P(BatchEngine, PartialPrecisionAndPowerStayWithinTheSpecTolerance) {
  const Vec4f expp = RunOnce("expp oPos, v0.z", {0, 0, 2.5f, 0}, ConstantBank());
  EXPECT_NEAR(expp[2], std::exp2(2.5f), std::exp2(2.5f) * std::ldexp(1.0f, -11));
  const Vec4f logp = RunOnce("logp oPos, v0.w", {0, 0, 0, 10}, ConstantBank());
  EXPECT_NEAR(logp[2], std::log2(10.0f), std::ldexp(1.0f, -11) * 4);
  const Vec4f lit = RunOnce("lit oPos, v0", {0.5f, 0.5f, 0, 2}, ConstantBank());
  EXPECT_NEAR(lit[2], 0.25f, 1.0f / 256);
}

// The paper's irradiance program (§9 listing, errata applied): oD0.rgb = eq. (7) for the normal v0.
constexpr const char* kIrradiance = R"(
dp4 r1.x, v0, c0
dp4 r1.y, v0, c1
dp4 r1.z, v0, c2
mul r2, v0.xyzz, v0.yzzx
dp4 r3.x, r2, c3
dp4 r3.y, r2, c4
dp4 r3.z, r2, c5
mul r4.xy, v0.xy, v0.xy
add r4.x, r4.x, -r4.y
mad r3.xyz, c6.xyz, r4.x, r3.xyz
add oD0.xyz, r1.xyz, r3.xyz
)";

ConstantBank RandomConstants(unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> value(-2, 2);
  ConstantBank bank;
  for (int reg = 0; reg < 16; ++reg) {
    for (int c = 0; c < 4; ++c) bank[reg][c] = value(rng);
  }
  return bank;
}

Vec4f RandomNormal(std::size_t i) {
  const float a = 0.37f * static_cast<float>(i), b = 0.11f * static_cast<float>(i);
  return {std::sin(a) * std::cos(b), std::sin(a) * std::sin(b), std::cos(a), 1};
}

// Eq. (7) with the program's operation order, one float operation at a time.
Vec4f IrradianceByHand(const Vec4f& n, const ConstantBank& c) {
  auto dp4 = [](const Vec4f& a, const Vec4f& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3]; };
  const Vec4f products = {n[0] * n[1], n[1] * n[2], n[2] * n[2], n[2] * n[0]};
  const float band = n[0] * n[0] + -(n[1] * n[1]);
  Vec4f result = {0, 0, 0, 0};  // oD0.w is never written: 0, as the slot is written
  for (int k = 0; k < 3; ++k) result[k] = dp4(n, c[k]) + (c[6][k] * band + dp4(products, c[3 + k]));
  return result;
}

TEST_P(BatchEngine, IrradianceProgramMatchesEquationSevenForAnyVertexCount) {
  const Program program = Assemble(kIrradiance);
  const ConstantBank constants = RandomConstants(7);
  auto engine = MakeBatchEngine(program, constants, {});
  for (std::size_t count : {1u, 7u, 255u, 256u, 257u, 1000u}) {
    VertexArrays inputs = Inputs(count, [](int, std::size_t i) { return RandomNormal(i); });
    VertexArrays outputs = MakeOutputArrays(count, program);
    ASSERT_EQ(engine->Run(inputs, outputs).message(), "");
    for (std::size_t i = 0; i < count; ++i) {
      ExpectBitsEqual(Lanes(outputs, static_cast<int>(OutputSlot::kDiffuse), i),
                      IrradianceByHand(RandomNormal(i), constants),
                      "count " + std::to_string(count) + " vertex " + std::to_string(i));
    }
  }
}

// Threads 1..4 on a pool of 4 (more than this machine's cores may have), kernels and compiled code,
// each engine run twice (the second call reuses its per-thread workspaces): every bit as one thread.
TEST_P(BatchEngine, ThreadsGiveTheSameBitsAsOneThread) {
  const Program program = Assemble(std::string(kIrradiance) +
                                   "mov a0.x, v1.x\nmad oT0, v0, c[a0.x + 2], -v1\nrsq oPos, v0.z\n");
  const ConstantBank constants = RandomConstants(11);
  ThreadPool pool(4);
  // Several pieces per thread, several batches each, a short last one.
  for (const std::size_t count : {1000u, 70000u, 300001u}) {
    VertexArrays inputs = Inputs(count, [](int reg, std::size_t i) {
      return reg == 1 ? Vec4f{static_cast<float>(i % 13) - 3, 0.5f, 0.25f, 2} : RandomNormal(i);
    });
    for (const bool compiled : {false, true}) {
      VertexArrays one = MakeOutputArrays(count, program);
      ASSERT_EQ(MakeBatchOrJit(compiled, program, constants, {1})->Run(inputs, one).message(), "");
      for (int threads = 1; threads <= 4; ++threads) {
        SCOPED_TRACE(std::to_string(count) + " vertices, " + std::to_string(threads) + " threads" +
                     (compiled ? ", compiled" : ", kernels"));
        std::unique_ptr<Engine> engine = MakeBatchOrJit(compiled, program, constants, {.threads = threads, .pool = &pool});
        for (int call = 0; call < 2; ++call) {
          VertexArrays many = MakeOutputArrays(count, program);
          ASSERT_EQ(engine->Run(inputs, many).message(), "");
          ExpectSameBits(many, one, count);
        }
      }
    }
  }
}

// Engines on one pool, called from several threads at once (one engine per thread: an engine is not
// shareable), each give one thread's bits.
TEST_P(BatchEngine, EnginesSharingOnePoolFromSeveralThreadsGiveOneThreadsBits) {
  const Program program = Assemble(std::string(kIrradiance));
  const ConstantBank constants = RandomConstants(5);
  constexpr std::size_t kCount = 100000;
  VertexArrays inputs = Inputs(kCount, [](int, std::size_t i) { return RandomNormal(i); });
  VertexArrays one = MakeOutputArrays(kCount, program);
  ASSERT_EQ(MakeBatchEngine(program, constants, {1})->Run(inputs, one).message(), "");
  ThreadPool pool(3);
  constexpr int kCallers = 3;
  std::vector<VertexArrays> results;
  for (int c = 0; c < kCallers; ++c) results.push_back(MakeOutputArrays(kCount, program));
  std::vector<std::thread> callers;
  for (int c = 0; c < kCallers; ++c) {
    callers.emplace_back([&, c] {
      std::unique_ptr<Engine> engine = MakeBatchOrJit(c % 2 == 1, program, constants, {.threads = 3, .pool = &pool});
      for (int call = 0; call < 3; ++call) {
        EXPECT_EQ(engine->Run(inputs, results[static_cast<std::size_t>(c)]).message(), "");
      }
    });
  }
  for (std::thread& caller : callers) caller.join();
  for (int c = 0; c < kCallers; ++c) ExpectSameBits(results[static_cast<std::size_t>(c)], one, kCount);
}

TEST_P(BatchEngine, AddressRegisterIsPerVertex) {
  const Program program = Assemble("mov a0.x, v1.x\nmov oPos, c[a0.x + 2]\n");
  ConstantBank constants;
  for (int reg = 0; reg < constants.size(); ++reg) constants[reg] = {static_cast<float>(reg), 0, 0, 1};
  const float inputs_x[] = {0, 1.9f, -2, -2.5f, 93, 94, 1e9f, -1e9f, std::numeric_limits<float>::infinity(),
                            std::nanf("")};
  const float expected_x[] = {2, 3, 0, 0, 95, 0, 0, 0, 0, 0};  // c[floor(x) + 2], 0 outside c0..c95
  const std::size_t count = std::size(inputs_x);
  VertexArrays inputs = Inputs(count, [&](int reg, std::size_t i) {
    return reg == 1 ? Vec4f{inputs_x[i], 0, 0, 0} : kDefaultInput;
  });
  VertexArrays outputs = MakeOutputArrays(count, program);
  ASSERT_EQ(MakeBatchEngine(program, constants, {})->Run(inputs, outputs).message(), "");
  for (std::size_t i = 0; i < count; ++i) {
    EXPECT_EQ(outputs.lane(kPosition, 0)[i], expected_x[i]) << "a0 from " << inputs_x[i];
  }
}

TEST_P(BatchEngine, OutputSlotsTheProgramDoesNotWriteGetTheirDefaults) {
  const Program program = Assemble("mov oPos.xy, v0\n");
  const int slots[] = {kPosition, static_cast<int>(OutputSlot::kDiffuse), static_cast<int>(OutputSlot::kSpecular),
                       static_cast<int>(OutputSlot::kTexCoord0)};
  VertexArrays outputs(3, slots, kOutputSlotCount);
  VertexArrays inputs = Inputs(3, [](int, std::size_t) { return Vec4f{5, 6, 7, 8}; });
  ASSERT_EQ(MakeBatchEngine(program, ConstantBank(), {})->Run(inputs, outputs).message(), "");
  for (std::size_t i = 0; i < 3; ++i) {
    ExpectBitsEqual(Lanes(outputs, kPosition, i), {5, 6, 0, 0}, "oPos");
    ExpectBitsEqual(Lanes(outputs, slots[1], i), {1, 1, 1, 1}, "oD0");
    ExpectBitsEqual(Lanes(outputs, slots[2], i), {0, 0, 0, 1}, "oD1");
    ExpectBitsEqual(Lanes(outputs, slots[3], i), {0, 0, 0, 0}, "oT0");
  }
}

TEST_P(BatchEngine, SkipsOutputsTheCallerDidNotAskFor) {
  const Program program = Assemble("mov oT3, v0\nadd oPos, v0, v0\n");
  VertexArrays outputs(300, std::vector<int>{kPosition}, kOutputSlotCount);
  VertexArrays inputs = Inputs(300, [](int, std::size_t i) { return Vec4f{static_cast<float>(i), 1, 2, 3}; });
  ASSERT_EQ(MakeBatchEngine(program, ConstantBank(), {})->Run(inputs, outputs).message(), "");
  for (std::size_t i = 0; i < 300; ++i) {
    ExpectBitsEqual(Lanes(outputs, kPosition, i), {2.0f * static_cast<float>(i), 2, 4, 6}, "oPos");
  }
}

TEST_P(BatchEngine, SetConstantsAndDefinitions) {
  const Program program = Assemble("def c1, 1, 2, 3, 4\nadd oPos, c0, c1\n");
  auto engine = MakeBatchEngine(program, Constants({{0, {10, 10, 10, 10}}, {1, {9, 9, 9, 9}}}), {});
  VertexArrays inputs = Inputs(1, [](int, std::size_t) { return kDefaultInput; });
  VertexArrays outputs = MakeOutputArrays(1, program);
  ASSERT_EQ(engine->Run(inputs, outputs).message(), "");
  ExpectBitsEqual(Lanes(outputs, kPosition, 0), {11, 12, 13, 14}, "def wins over the API value");
  ASSERT_EQ(engine->SetConstants(Constants({{0, {100, 100, 100, 100}}})).message(), "");
  ASSERT_EQ(engine->Run(inputs, outputs).message(), "");
  ExpectBitsEqual(Lanes(outputs, kPosition, 0), {101, 102, 103, 104}, "after SetConstants");
}

TEST_P(BatchEngine, RunsNoVertices) {
  const Program program = Assemble("mov oPos, v0\n");
  VertexArrays inputs = Inputs(0, [](int, std::size_t) { return kDefaultInput; });
  VertexArrays outputs = MakeOutputArrays(0, program);
  ASSERT_EQ(MakeBatchEngine(program, ConstantBank(), {2})->Run(inputs, outputs).message(), "");
  EXPECT_EQ(outputs.count(), 0u);
}

}  // namespace
}  // namespace vs11
