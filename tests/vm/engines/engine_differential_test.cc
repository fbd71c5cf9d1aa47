// The batch engine against the reference engine, bit for bit (NaN equals NaN only with the same
// bits), on every Highway target this build compiled and the CPU supports, and the jit engine (the
// program compiled to machine code) likewise at every instruction set the CPU supports (AVX2,
// AVX-512), each forced in turn:
//  * every executable opcode x write masks x swizzles x negations x operand files, over vertices
//    whose lanes run through the special values (signed zeros, denormals, infinities, NaNs, the
//    limits of exp and of a0);
//  * thousands of random programs (all opcodes incl. macros, every register file, relative
//    addressing, def, unwritten temporaries) over random inputs and constants;
// each under both float rules (vm/core/float_rules.h), d3d9 and legacy.
#include <algorithm>
#include <array>
#include <bit>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <initializer_list>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "hwy/highway.h"
#include "hwy/tests/hwy_gtest.h"
#include "vm/asm/disassembler.h"
#include "vm/engines/batch_engine.h"
#include "vm/engines/engine_factory.h"
#include "vm/engines/jit_compiler.h"
#include "vm/engines/reference_engine.h"
#include "tests/vm/engines/random_program.h"

namespace vs11 {
namespace {

using namespace vs11::random_program;  // NOLINT: the generator and its register helpers

// How strictly NaN results are compared. When an operation meets two NaNs with different bits, IEEE
// 754 leaves open which one it returns; x86 returns its first operand, and which C++ operand the
// compiler makes the first one of an add or a mul is its free choice at each call site (it differs
// even between call sites of the reference engine). The engines therefore agree on the bits of a
// NaN only when a single NaN (or the invalid-operation default NaN) reaches each operation: tests
// that can meet two NaNs accept any NaN for a NaN, and LoneNaNOperandKeepsItsBits checks the bits.
enum class NanBits { kExact, kAnyNaN };

struct Comparison {
  std::string difference;        // the first lane that differs, empty if none
  std::size_t nan_bit_mismatches = 0;  // NaN lanes with different NaN bits (kAnyNaN only)
};

bool IsNaN(float x) { return x != x; }

// The engine compared with the reference: its kind and, for the jit, the instruction set forced;
// both run under `rules`.
struct EngineUnderTest {
  std::string kind;
  JitIsa jit_isa = JitIsa::kBest;
  FloatRules rules = FloatRules::kD3d9;
};

// Runs `program` on both engines and compares every output lane.
Comparison CompareEngines(const Program& program, const ConstantBank& constants, const VertexArrays& inputs,
                          NanBits nan_bits, EngineUnderTest engine) {
  const std::size_t count = inputs.count();
  VertexArrays expected = MakeOutputArrays(count, program);
  VertexArrays actual = MakeOutputArrays(count, program);
  EXPECT_EQ(MakeReferenceEngine(program, constants, engine.rules)->Run(inputs, expected).message(), "");
  EXPECT_EQ(MakeEngine(engine.kind, program, constants, WithJitIsa({.float_rules = engine.rules}, engine.jit_isa))
                .value()
                ->Run(inputs, actual)
                .message(),
            "");
  Comparison result;
  for (int slot : expected.registers()) {
    for (int c = 0; c < 4; ++c) {
      for (std::size_t i = 0; i < count; ++i) {
        const float want = expected.lane(slot, c)[i], got = actual.lane(slot, c)[i];
        if (Bits(want) == Bits(got)) continue;
        if (nan_bits == NanBits::kAnyNaN && IsNaN(want) && IsNaN(got)) {
          ++result.nan_bit_mismatches;
          continue;
        }
        if (!result.difference.empty()) continue;
        std::ostringstream message;
        message << kFloatRulesNames.Name(engine.rules) << ": " << OutputSlotName(slot) << "." << kLaneLetters[c] << " of vertex " << i << " of " << count
                << ": " << engine.kind << " " << got << " (0x" << std::hex << Bits(got) << "), reference " << want << " (0x"
                << Bits(want) << std::dec << ")\ninputs:";
        for (int reg : inputs.registers()) {
          message << " v" << reg << "=(";
          for (int k = 0; k < 4; ++k) message << (k ? ", " : "") << inputs.lane(reg, k)[i];
          message << ")";
        }
        message << "\nprogram:\n" << Disassemble(program);
        result.difference = message.str();
      }
    }
  }
  return result;
}

class EngineDifferential : public hwy::TestWithParamTarget {};
HWY_TARGET_INSTANTIATE_TEST_SUITE_P(EngineDifferential);

// ---- the sweep --------------------------------------------------------------------------------------

void SweepEveryOpcode(EngineUnderTest engine, const char* label) {
  const std::vector<float>& special = SpecialValues();
  const std::size_t n = special.size();
  // Vertex i pairs every special value of v0 with every one of v1 (v2 and v3 vary too), lane by lane
  // rotated so that each lane sees each pair.
  const std::size_t count = n * n;
  VertexArrays inputs = MakeInputArrays(count, kInputs);
  for (std::size_t i = 0; i < count; ++i) {
    for (int c = 0; c < 4; ++c) {
      const std::size_t k = static_cast<std::size_t>(c);
      inputs.lane(0, c)[i] = special[(i + k) % n];
      inputs.lane(1, c)[i] = special[(i / n + 3 * k) % n];
      inputs.lane(2, c)[i] = special[(i * 7 + 5 * k) % n];
      inputs.lane(3, c)[i] = static_cast<float>(static_cast<int>(i % 11) - 3) + 0.5f * static_cast<float>(k);
    }
  }
  ConstantBank constants;
  for (int reg = 0; reg < constants.size(); ++reg) {
    for (int c = 0; c < 4; ++c) constants[reg][c] = special[static_cast<std::size_t>(reg * 4 + c) % n];
  }
  const Swizzle swizzles[] = {Swizzle(), Swizzle::Replicate(0), Swizzle::Replicate(3), Swizzle(0x1B) /* wzyx */,
                              Swizzle(0x39) /* yzwx */};
  // Operand files: temporaries, then constants (absolute and relative, a0 from v3.x) in each position.
  enum class Files { kTemps, kConstantFirst, kRelativeSecond };

  int programs = 0;
  std::size_t nan_bit_mismatches = 0;
  for (const OpcodeInfo& info : kOpcodeTable) {
    if (!info.is_executable() || info.kind == ResultKind::kNoResult || info.since != ShaderModel::kVs11) continue;
    std::vector<WriteMask> masks = LegalMasks(info);
    if (info.mask_rule == MaskRule::kAny) masks = {WriteMask(0x1), WriteMask(0xA), WriteMask(0x7), WriteMask(0xF)};
    if (info.kind == ResultKind::kMatrix) masks.push_back(WriteMask(0xD));  // beyond the rows: unvalidated
    const int arity = info.source_count();
    for (Files files : {Files::kTemps, Files::kConstantFirst, Files::kRelativeSecond}) {
      for (WriteMask mask : masks) {
        for (const Swizzle& swizzle : swizzles) {
          for (int negations = 0; negations < (1 << arity); ++negations) {
            Program program;
            auto& code = program.instructions;
            code.push_back(MakeInstruction(Opcode::kMov, {Temp(1), WriteMask()}, {Src(Input(1))}));
            code.push_back(MakeInstruction(Opcode::kMov, {Temp(2), WriteMask()}, {Src(Input(2))}));
            code.push_back(MakeInstruction(Opcode::kMov, {Temp(3), WriteMask()}, {Src(Input(2), Swizzle(0x39))}));
            code.push_back(MakeInstruction(Opcode::kMov, {Temp(4), WriteMask()}, {Src(Input(1), Swizzle(0x1B))}));
            code.push_back(MakeInstruction(Opcode::kMov, {kAddressRegister, WriteMask(0x1)}, {Src(Input(3))}));
            std::array<RegisterRef, 3> regs = {Input(0), Temp(1), Temp(2)};
            if (files == Files::kConstantFirst) regs = {Const(programs % 16), Input(0), Temp(1)};
            if (files == Files::kRelativeSecond) regs = {Temp(1), Const(2 + programs % 8, true), Input(0)};
            Instruction op;
            op.opcode = info.opcode;
            for (int s = 0; s < arity; ++s) {
              // The second source keeps its identity swizzle, so the two differ.
              op.sources[s] = Src(regs[s], s == 1 ? Swizzle() : swizzle, (negations >> s) & 1);
            }
            op.dest = {Temp(0), mask};
            code.push_back(op);
            code.push_back(MakeInstruction(Opcode::kMov, {Output(0), WriteMask()}, {Src(Temp(0))}));
            op.dest = {Output(static_cast<int>(OutputSlot::kDiffuse)), mask};  // straight to an output
            code.push_back(op);
            op.dest = {Temp(2), mask};  // onto one of its own sources
            code.push_back(op);
            code.push_back(MakeInstruction(Opcode::kMov, {Output(static_cast<int>(OutputSlot::kTexCoord0)), WriteMask()},
                                           {Src(Temp(2))}));
            ++programs;
            const Comparison comparison = CompareEngines(program, constants, inputs, NanBits::kAnyNaN, engine);
            ASSERT_TRUE(comparison.difference.empty()) << comparison.difference;
            nan_bit_mismatches += comparison.nan_bit_mismatches;
          }
        }
      }
    }
  }
  std::printf("[ %s, %s ] %d programs x %zu vertices compared bit for bit (%zu lanes: NaN from two NaNs)\n", label,
              std::string(kFloatRulesNames.Name(engine.rules)).c_str(), programs, count, nan_bit_mismatches);
}

TEST_P(EngineDifferential, EveryOpcodeMaskSwizzleNegationAndSpecialValue) {
  for (FloatRules rules : kAllFloatRules) {
    SweepEveryOpcode({"batch", JitIsa::kBest, rules}, hwy::TargetName(GetParam()));
  }
}

// Every operand position of every opcode, negated or not, carrying one NaN (quiet or signalling, either
// sign, with a payload) in one lane while every other value is ordinary: the result's bits must match.
void CheckLoneNaNOperands(EngineUnderTest engine, const char* label) {
  const std::uint32_t nans[] = {0x7FC12345u, 0xFFC0ABCDu, 0x7F800001u, 0xFF812345u};
  const float ordinary[3][4] = {{0.75f, -1.5f, 2.0f, 3.25f}, {-0.5f, 4.0f, 1.25f, -2.0f}, {1.5f, 0.25f, -3.0f, 5.0f}};
  const int inputs_used[] = {0, 1, 2, 3, 4};  // m4x4 rows of v1 reach v4
  // Vertex (nan, source, lane): the NaN in that lane of that source, all else ordinary.
  const std::size_t count = std::size(nans) * 3 * 4;
  VertexArrays inputs = MakeInputArrays(count, inputs_used);
  for (std::size_t i = 0; i < count; ++i) {
    const std::size_t nan = i / 12, source = i / 4 % 3, lane = i % 4;
    for (int reg : inputs_used) {
      for (int c = 0; c < 4; ++c) {
        const bool here = static_cast<std::size_t>(reg) == source && static_cast<std::size_t>(c) == lane;
        inputs.lane(reg, c)[i] = here ? std::bit_cast<float>(nans[nan]) : ordinary[reg % 3][c];
      }
    }
  }
  int programs = 0;
  for (const OpcodeInfo& info : kOpcodeTable) {
    if (!info.is_executable() || info.kind == ResultKind::kNoResult || info.since != ShaderModel::kVs11) continue;
    const int arity = info.source_count();
    for (const Swizzle& swizzle : {Swizzle(), Swizzle(0x1B)}) {
      for (int negations = 0; negations < (1 << arity); ++negations) {
        Instruction op;
        op.opcode = info.opcode;
        for (int s = 0; s < arity; ++s) op.sources[s] = Src(Input(s), swizzle, (negations >> s) & 1);
        op.dest = {Output(0), LegalMasks(info).back()};
        Program program;
        program.instructions.push_back(op);
        ++programs;
        const Comparison comparison = CompareEngines(program, ConstantBank(), inputs, NanBits::kExact, engine);
        ASSERT_TRUE(comparison.difference.empty()) << comparison.difference;
      }
    }
  }
  std::printf("[ %s, %s ] %d programs x %zu vertices compared bit for bit, NaNs included\n", label,
              std::string(kFloatRulesNames.Name(engine.rules)).c_str(), programs, count);
}

TEST_P(EngineDifferential, LoneNaNOperandKeepsItsBits) {
  for (FloatRules rules : kAllFloatRules) {
    CheckLoneNaNOperands({"batch", JitIsa::kBest, rules}, hwy::TargetName(GetParam()));
  }
}

// ---- random programs --------------------------------------------------------------------------------

// Scaled by VS11_DIFFERENTIAL_PROGRAMS for longer soaks.
int RandomProgramCount() {
  const char* text = std::getenv("VS11_DIFFERENTIAL_PROGRAMS");
  return text != nullptr ? std::max(1, std::atoi(text)) : 3000;
}

struct JitCoverage {
  int compiled = 0;  // programs the jit compiler compiled under both rules (all, on a CPU with AVX2)
  int spilling = 0;  // of which the register allocator spilled values
};

// Each program under both float rules. For kJit, also says how many programs ran as machine code.
JitCoverage CompareRandomPrograms(EngineUnderTest engine, const char* label) {
  const int programs = RandomProgramCount();
  ProgramGenerator generator(20240611);
  std::size_t vertices = 0, nan_bit_mismatches = 0;
  JitCoverage coverage;
  std::mt19937 sizes(5);
  for (int k = 0; k < programs; ++k) {
    const Program program = generator.MakeProgram();
    const ConstantBank constants = generator.Constants();
    // Mostly short runs (with tails not a multiple of any vector), sometimes several batches.
    const std::size_t count = k % 10 == 0 ? std::uniform_int_distribution<std::size_t>(257, 1500)(sizes)
                                          : std::uniform_int_distribution<std::size_t>(1, 100)(sizes);
    vertices += count;
    const VertexArrays inputs = generator.Inputs(count);
    for (FloatRules rules : kAllFloatRules) {
      engine.rules = rules;
      const Comparison comparison = CompareEngines(program, constants, inputs, NanBits::kAnyNaN, engine);
      EXPECT_TRUE(comparison.difference.empty()) << "random program " << k << ": " << comparison.difference;
      if (!comparison.difference.empty()) return coverage;
      nan_bit_mismatches += comparison.nan_bit_mismatches;
    }
    if (engine.kind != "jit") continue;
    std::string why_not;
    const auto compiled = jit::Compile(program, why_not, engine.jit_isa);
    if (compiled && jit::Compile(program, why_not, engine.jit_isa, {}, FloatRules::kLegacy)) {
      ++coverage.compiled;
      if (compiled->spilled_values() > 0) ++coverage.spilling;
    }
  }
  std::printf("[ %s ] %d random programs under both float rules, %zu vertices compared bit for bit (%zu lanes: NaN "
              "from two NaNs)\n", label, programs, vertices, nan_bit_mismatches);
  return coverage;
}

TEST_P(EngineDifferential, RandomProgramsMatchBitForBit) {
  CompareRandomPrograms({"batch"}, hwy::TargetName(GetParam()));
}

// ---- the jit engine -----------------------------------------------------------------------------------

// One instance per instruction set the CPU runs, so none is left untested where it exists.
class JitDifferential : public testing::TestWithParam<JitIsa> {
 protected:
  EngineUnderTest Engine() const { return {"jit", GetParam()}; }
  std::string Label() const { return std::string("jit ").append(kJitIsaNames.Name(GetParam())); }
};
INSTANTIATE_TEST_SUITE_P(SupportedIsas, JitDifferential, testing::ValuesIn(jit::SupportedIsas()),
                         [](const testing::TestParamInfo<JitIsa>& info) { return std::string(kJitIsaNames.Name(info.param)); });
// A CPU without AVX2 has no instance: there the jit engine runs the batch kernels, tested above.
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(JitDifferential);

// The instruction sets the jit tests cover are the ones the CPU reports (a jit that failed to detect
// AVX-512 would otherwise leave its code untested without a word).
TEST(JitIsas, TheTestsCoverEveryInstructionSetTheCpuHas) {
  std::vector<JitIsa> expected;
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx2")) expected.push_back(JitIsa::kAvx2);
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("avx512f")) {
    expected.push_back(JitIsa::kAvx512);
  }
  EXPECT_EQ(jit::SupportedIsas(), expected);
  std::string covered;
  for (JitIsa isa : jit::SupportedIsas()) covered.append(" ").append(kJitIsaNames.Name(isa));
  std::printf("[ jit ] instruction sets covered:%s\n", covered.empty() ? " none (no AVX2: batch kernels)" : covered.c_str());
}

TEST_P(JitDifferential, EveryOpcodeMaskSwizzleNegationAndSpecialValue) {
  for (FloatRules rules : kAllFloatRules) SweepEveryOpcode({"jit", GetParam(), rules}, Label().c_str());
}

TEST_P(JitDifferential, LoneNaNOperandKeepsItsBits) {
  for (FloatRules rules : kAllFloatRules) CheckLoneNaNOperands({"jit", GetParam(), rules}, Label().c_str());
}

// A lane's uniform value is a promise that ends when the lane is written through lane(): the same
// engine then reads the new values. Output lanes the program leaves alone are rewritten only when
// they may have changed.
TEST_P(JitDifferential, UniformLanesFollowTheirPromise) {
  Program program;
  // oD0.xyz = v0.w * c0 + v1 (oD0.w untouched); with v0.w uniform 2 the product is compiled in.
  program.instructions.push_back(MakeInstruction(Opcode::kMad, {Output(static_cast<int>(OutputSlot::kDiffuse)), WriteMask(0x7)},
                                                 {Src(Input(0), Swizzle(0xFF)), Src(Const(0)), Src(Input(1))}));
  ConstantBank constants;
  constants[0] = {1.5f, -2.0f, 0.25f, 8.0f};
  const std::size_t count = 1000;
  VertexArrays inputs = MakeInputArrays(count, kInputs);
  inputs.FillUniform(0, 3, 2.0f);
  for (std::size_t i = 0; i < count; ++i) {
    for (int c = 0; c < 4; ++c) inputs.lane(1, c)[i] = static_cast<float>(i) * 0.5f - static_cast<float>(c);
  }
  std::unique_ptr<vs11::Engine> engine = MakeEngine("jit", program, constants, WithJitIsa({}, GetParam())).value();
  const auto check = [&](const char* when) {
    VertexArrays expected = MakeOutputArrays(count, program);
    ASSERT_EQ(MakeReferenceEngine(program, constants)->Run(inputs, expected).message(), "");
    VertexArrays actual = MakeOutputArrays(count, program);
    actual.lane(static_cast<int>(OutputSlot::kDiffuse), 3)[7] = 42.0f;  // a stale value: must be rewritten
    ASSERT_EQ(engine->Run(inputs, actual).message(), "");
    for (int c = 0; c < 4; ++c) {
      for (std::size_t i = 0; i < count; ++i) {
        ASSERT_EQ(Bits(std::as_const(actual).lane(static_cast<int>(OutputSlot::kDiffuse), c)[i]),
                  Bits(std::as_const(expected).lane(static_cast<int>(OutputSlot::kDiffuse), c)[i]))
            << when << ": oD0." << kLaneLetters[c] << " of vertex " << i;
      }
    }
  };
  check("v0.w uniform 2");
  inputs.lane(0, 3)[500] = -3.0f;  // the promise ends
  check("v0.w written");
  inputs.FillUniform(0, 3, std::bit_cast<float>(0x7FC12345u));  // a NaN, compiled in with its bits
  check("v0.w uniform NaN");
}

// Eight compares whose masks are used again at the end of the program (min reuses slt's a < b):
// more masks alive than AVX-512 has mask registers for, so some are spilled and reloaded. Run over
// a few vertices, and over enough that the outputs are stored around the caches.
TEST_P(JitDifferential, SpilledMasksAndStreamedOutputsMatch) {
  Program program;
  constexpr int kCompares = 8;
  const int first_output = static_cast<int>(OutputSlot::kTexCoord0);
  const auto lane_of = [&](int slot, int k) { return std::pair{Output(slot + k / 4), WriteMask(1 << (k % 4))}; };
  for (int k = 0; k < kCompares; ++k) {
    const auto [reg, mask] = lane_of(first_output, k);
    program.instructions.push_back(
        MakeInstruction(Opcode::kSlt, {reg, mask}, {Src(Input(k % 2), Swizzle::Replicate(k / 2)), Src(Const(k))}));
  }
  for (int k = 0; k < kCompares; ++k) {
    const auto [reg, mask] = lane_of(first_output + 2, k);
    program.instructions.push_back(
        MakeInstruction(Opcode::kMin, {reg, mask}, {Src(Input(k % 2), Swizzle::Replicate(k / 2)), Src(Const(k))}));
  }
  ConstantBank constants;
  for (int k = 0; k < kCompares; ++k) {
    const float value = 0.2f * static_cast<float>(k) - 0.7f;
    constants[k] = {value, -value, value, -value};
  }
  std::string why_not;
  const auto compiled = jit::Compile(program, why_not, GetParam());
  ASSERT_NE(compiled, nullptr) << why_not;
  if (GetParam() == JitIsa::kAvx512) {
    EXPECT_GT(compiled->spilled_masks(), 0);
  }
  const std::size_t stored_lanes = 4 * kCompares / 2;
  const std::size_t streamed = 2 * jit::kStreamingOutputBytes / (sizeof(float) * stored_lanes);
  for (const std::size_t count : {std::size_t{100}, streamed}) {
    VertexArrays inputs = MakeInputArrays(count, kInputs);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
    for (int reg : {0, 1}) {
      for (int c = 0; c < 4; ++c) {
        float* lane = inputs.lane(reg, c);
        for (std::size_t i = 0; i < count; ++i) lane[i] = uniform(rng);
      }
    }
    const Comparison comparison = CompareEngines(program, constants, inputs, NanBits::kExact, Engine());
    EXPECT_TRUE(comparison.difference.empty()) << count << " vertices: " << comparison.difference;
  }
}

// Lanes start on cache lines (the jit's streaming stores need vector-aligned lanes), and an odd
// number of lines apart, so that the same vertex of different lanes falls in different cache sets.
TEST(VertexArraysLayout, LanesStartOnCacheLinesAnOddNumberOfLinesApart) {
  for (const std::size_t count : {std::size_t{1}, std::size_t{16}, std::size_t{1000}, std::size_t{1024}, std::size_t{65536}}) {
    VertexArrays inputs = MakeInputArrays(count, kInputs);
    const auto address = [&](int reg, int c) { return reinterpret_cast<std::uintptr_t>(std::as_const(inputs).lane(reg, c)); };
    for (int reg : kInputs) {
      for (int c = 0; c < 4; ++c) {
        EXPECT_EQ(address(reg, c) % 64, 0u) << count;
        const std::uintptr_t next = c < 3 ? address(reg, c + 1) : reg < 3 ? address(reg + 1, 0) : 0;
        if (next == 0) continue;
        EXPECT_GE(next - address(reg, c), count * sizeof(float)) << count;
        if (count > 16) {
          EXPECT_EQ((next - address(reg, c)) / 64 % 2, 1u) << count;
        }
      }
    }
  }
}

TEST(VertexArraysUniform, FillMarksAndWritingThroughLaneUnmarks) {
  const int registers[] = {0};
  VertexArrays inputs = MakeInputArrays(4, registers);
  EXPECT_EQ(std::as_const(inputs).uniform(0, 3), 1.0f);  // the default w nobody supplied
  EXPECT_EQ(std::as_const(inputs).uniform(0, 0), 0.0f);
  inputs.lane(0, 0)[2] = 5.0f;
  EXPECT_FALSE(inputs.uniform(0, 0).has_value());
  inputs.FillUniform(0, 0, -1.0f);
  EXPECT_EQ(inputs.uniform(0, 0), -1.0f);
  EXPECT_EQ(std::as_const(inputs).lane(0, 0)[2], -1.0f);
}

TEST_P(JitDifferential, RandomProgramsMatchBitForBit) {
  const JitCoverage coverage = CompareRandomPrograms(Engine(), Label().c_str());
  // Every program compiles (so none ran on the batch kernels instead), and enough of them keep more
  // values alive than there are registers that the spill path runs too.
  std::printf("[ %s ] %d of %d random programs compiled, %d of them spilling registers\n", Label().c_str(),
              coverage.compiled, RandomProgramCount(), coverage.spilling);
  EXPECT_EQ(coverage.compiled, RandomProgramCount());
  EXPECT_GT(coverage.spilling, RandomProgramCount() / 20);
}

}  // namespace
}  // namespace vs11
