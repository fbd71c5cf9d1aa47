// The batch and jit engines on later-model programs with static flow control (vm/core/static_flow.h,
// vm/engines/static_flow_engine.h): random vs_2_x programs with nested rep/loop reading c[aL + n], if
// on b#, call/callnz on b#, loops that run zero times and breaks from nested loops, run by ref, batch
// and jit on every instruction set the CPU has under both float rules, compared bit for bit.
#include <cmath>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "tests/vm/engines/later_model_comparison.h"
#include "vm/core/static_flow.h"
#include "vm/engines/static_flow_engine.h"

namespace vs11 {
namespace {

using namespace later_model;  // NOLINT(build/namespaces): the shared comparison of these tests

constexpr int kBankSize = 256;

// A random vs_2_x program whose flow depends on i0-i3 and b0-b3 only.
class ProgramWriter : later_model::Draws {
 public:
  explicit ProgramWriter(unsigned seed) : Draws(seed) {}

  std::string Write() {
    std::string text = "vs_2_x\n";  // break is vs_2_x's

    for (int i = 0; i < 4; ++i) {
      text += fmt::format("defi i{}, {}, {}, {}, 0\n", i, Pick(-1, 3), Pick(-3, 250), Pick(-2, 3));
      text += fmt::format("defb b{}, {}\n", i, Pick(0, 1) ? "true" : "false");
    }
    text += "dcl_position v0\ndcl_normal v1\nmov r0, v0\nmov r1, v1\nmov r2, c1\nmov r3, c2\n";
    text += Block(0, 0, false, true);
    text += "mov oPos, r0\nmov oD0, r1\nmov oT0, r2\nmov oT1, r3\nret\nlabel l0\n" + Block(0, 0, false, false) +
            "ret\nlabel l1\n" + Block(0, 0, false, false) + "ret\n";
    return text;
  }

 private:
  std::string Source(bool in_loop, Reads& reads) {
    std::string text = Pick(0, 3) == 0 ? "-" : "";  // (appended to: GCC 12 warns on "-" + string)
    text += Register(in_loop, reads, 255, 8);
    return text + SwizzleSuffix();
  }
  std::string Arithmetic(bool in_loop) {
    static constexpr const char* kTwo[] = {"add", "mul", "dp3", "dp4", "min", "max", "slt", "sge"};
    Reads reads;
    const auto source = [&] { return Source(in_loop, reads); };
    switch (Pick(0, 3)) {
      case 0: {
        const std::string dest = Temp(), s0 = source(), s1 = source(), s2 = source();
        return fmt::format("mad {}, {}, {}, {}\n", dest, s0, s1, s2);
      }
      case 1: return fmt::format("mov {}, {}\n", Temp(), source());
      case 2: return fmt::format("m4x4 {}, {}, c{}\n", Temp(), Temp(), Pick(0, 252));
      default: {
        const std::string op = kTwo[Pick(0, 7)], dest = Temp(), s0 = source(), s1 = source();
        return fmt::format("{} {}, {}, {}\n", op, dest, s0, s1);
      }
    }
  }
  // Statements at nesting `depth` (`loops` rep/loop blocks around, `in_loop`: a loop with aL among them),
  // calls and loops only in the main program (the validator keeps aL out of subroutines).
  std::string Block(int depth, int loops, bool in_loop, bool main) {
    std::string text;
    for (int n = Pick(1, 4); n > 0; --n) {
      const int kind = depth < 3 ? Pick(0, 9) : 0;
      const std::string condition = fmt::format("{}b{}", Pick(0, 1) ? "!" : "", Pick(0, 3));
      if (kind <= 3) {
        text += Arithmetic(in_loop);
      } else if (kind == 4) {
        text += fmt::format("rep i{}\n", Pick(0, 3)) + Block(depth + 1, loops + 1, in_loop, main) + "endrep\n";
      } else if (kind == 5 && main) {
        text += fmt::format("loop aL, i{}\n", Pick(0, 3)) + Block(depth + 1, loops + 1, true, main) + "endloop\n";
      } else if (kind == 6) {
        text += "if " + condition + "\n" + Block(depth + 1, loops, in_loop, main) +
                (Pick(0, 1) ? "else\n" + Block(depth + 1, loops, in_loop, main) : "") + "endif\n";
      } else if (kind == 7 && loops > 0) {
        text += "if " + condition + "\nbreak\nendif\n";
      } else if (kind == 8 && main) {
        text += Pick(0, 1) ? "call l0\n" : "callnz l1, " + condition + "\n";
      } else {
        text += Arithmetic(in_loop);
      }
    }
    return text;
  }
};

ConstantBank RandomBank(std::mt19937& random) {
  std::uniform_real_distribution<float> value(-2.0f, 2.0f);
  ConstantBank bank(kBankSize);
  for (int k = 0; k < kBankSize; ++k) bank[k] = {value(random), value(random), value(random), value(random)};
  return bank;
}

VertexArrays InputsFrom(std::mt19937& random, std::size_t count) {
  std::uniform_real_distribution<float> value(-3.0f, 3.0f);
  return later_model::RandomInputs(count, [&] { return value(random); });
}

TEST(StaticFlow, RandomProgramsMatchTheReferenceBitForBit) {
  const char* env = std::getenv("VS11_STATIC_FLOW_PROGRAMS");
  const int programs = env != nullptr ? std::atoi(env) : 60;
  std::mt19937 random(33);
  int specialised = 0;
  for (int p = 0; p < programs; ++p) {
    const std::string source = ProgramWriter(static_cast<unsigned>(p)).Write();
    const Program program = Assemble(source);
    if (program.instructions.empty()) continue;
    const ConstantBank bank = RandomBank(random);
    const VertexArrays inputs = InputsFrom(random, 37);
    for (FloatRules rules : kAllFloatRules) {
      const VertexArrays expected = RunOn("ref", program, bank, inputs, {.float_rules = rules});
      for (const Candidate& candidate : Candidates(rules)) {
        const std::string& engine = candidate.engine;
        if (Result<std::unique_ptr<Engine>> made = MakeEngine(engine, program, bank, candidate.options); !made) {
          // Only the unrolled length may stop a program of this writer.
          EXPECT_NE(made.message().find("unrolled"), std::string::npos) << made.message();
          continue;
        }
        ++specialised;
        const std::string difference = Difference(expected, RunOn(engine, program, bank, inputs, candidate.options));
        EXPECT_EQ(difference, "") << candidate.name << ", " << kFloatRulesNames.Name(rules) << ", program " << p
                                  << ":\n" << source;
      }
    }
  }
  EXPECT_GT(specialised, programs);  // most programs ran specialised
}

// Hand-written corners: c[aL + n] before c0 and past the bank, an output written only in a branch not
// taken (oD0 then reads 0, not the unwritten (1, 1, 1, 1)), vs_3_0's o[aL] and v[aL] through their
// declarations, and a call from inside a loop.
TEST(StaticFlow, CornersMatchTheReference) {
  const char* const kPrograms[] = {
      ("vs_2_0\ndefi i0, 4, -2, 1, 0\ndefi i1, 3, 253, 1, 0\ndcl_position v0\nmov r0, v0\n"
      "loop aL, i0\nadd r0, r0, c[aL + 0]\nendloop\nloop aL, i1\nm4x4 r1, r0, c[aL + 0]\nadd r0, r0, r1\n"
      "endloop\nmov oPos, r0\n"),
      "vs_2_0\ndefb b0, false\ndcl_position v0\nmov oPos, v0\nif b0\nmov oD0.xy, v0\nmov oD1.x, v0\nendif\n",
      ("vs_3_0\ndefi i0, 3, 0, 1, 0\ndcl_position v0\ndcl_texcoord v1\ndcl_texcoord v2\ndcl_position o0\n"
      "dcl_texcoord0 o1\ndcl_texcoord1 o2\ndcl_color o3\nmov o0, v0\nloop aL, i0\nadd o1[aL], v0[aL], c[aL + 7]\n"
      "endloop\n"),
      ("vs_2_0\ndefi i0, 3, 5, 2, 0\ndcl_position v0\nmov r0, v0\nloop aL, i0\ncall l0\nadd r0, r0, c[aL + 1]\n"
      "endloop\nmov oPos, r0\nret\nlabel l0\nmul r0, r0, c2\nret\n"),
  };
  std::mt19937 random(7);
  for (const char* source : kPrograms) {
    const Program program = Assemble(source);
    const ConstantBank bank = RandomBank(random);
    VertexArrays inputs = InputsFrom(random, 19);
    for (FloatRules rules : kAllFloatRules) {
      const VertexArrays expected = RunOn("ref", program, bank, inputs, {.float_rules = rules});
      for (const Candidate& candidate : Candidates(rules)) {
        const std::string& engine = candidate.engine;
        EXPECT_EQ(Difference(expected, RunOn(engine, program, bank, inputs, candidate.options)), "")
            << candidate.name << ", " << kFloatRulesNames.Name(rules) << ":\n" << source;
      }
    }
  }
}

// Bones from i0: the loop's count is compiled into each specialisation.
constexpr const char* kSkinning =
    "vs_2_0\ndcl_position v0\nmov r0, c0\nloop aL, i0\nmad r0, v0, c[aL + 10], r0\nendloop\nmov oPos, r0\n";

TEST(StaticFlow, NewIntegerConstantsChangeTheUnrollingAndKnownOnesHitTheCache) {
  const Program program = Assemble(kSkinning);
  ConstantBank bank(kBankSize);
  for (int k = 0; k < kBankSize; ++k) bank[k] = {float(k), 1, 1, 1};
  bank.integer(0) = {2, 0, 1, 0};
  const std::vector<int> registers = {0};
  VertexArrays inputs = MakeInputArrays(1, registers);
  for (int c = 0; c < 4; ++c) inputs.FillUniform(0, c, 1.0f);
  for (const std::string engine_name : {"batch", "jit"}) {
    std::unique_ptr<Engine> engine = MakeEngine(engine_name, program, bank, {}).value();
    auto position_x = [&] {
      VertexArrays outputs = MakeOutputArrays(1, program);
      EXPECT_EQ(engine->Run(inputs, outputs).message(), "");
      return outputs.lane(static_cast<int>(OutputSlot::kPosition), 0)[0];
    };
    EXPECT_EQ(position_x(), 0.0f + 10 + 11);  // c0.x + c[aL + 10].x for aL = 0, 1
    EXPECT_EQ(SpecialisationCount(*engine), 1);
    bank.integer(0) = {3, 1, 2, 0};  // aL = 1, 3, 5
    ASSERT_EQ(engine->SetConstants(bank).message(), "");
    EXPECT_EQ(SpecialisationCount(*engine), 2);
    EXPECT_EQ(position_x(), 11.0f + 13 + 15);
    bank[0] = {100, 0, 0, 0};  // a float constant: the same specialisation
    ASSERT_EQ(engine->SetConstants(bank).message(), "");
    EXPECT_EQ(position_x(), 100.0f + 11 + 13 + 15);
    bank.integer(0) = {2, 0, 1, 0};  // back to the first: from the cache
    ASSERT_EQ(engine->SetConstants(bank).message(), "");
    EXPECT_EQ(SpecialisationCount(*engine), 2) << engine_name;
    EXPECT_EQ(position_x(), 100.0f + 10 + 11);
    bank[0] = {};
  }
}

// Dynamic flow (tests/vm/engines/dynamic_flow_test.cc) and the later arithmetic rows
// (tests/vm/engines/later_arithmetic_test.cc) run on batch and jit too.
TEST(StaticFlow, MovaAndDynamicFlowRunOnBatchAndJit) {
  const Program dynamic = Assemble(
      "vs_2_x\ndcl_position v0\nmov r0, v0\nif_gt r0.x, c0.x\nadd r0, r0, c1\nendif\nmov oPos, r0\n");
  const Program mova = Assemble("vs_2_0\ndcl_position v0\nmova a0.x, v0.x\nmov oPos, c[a0.x + 1]\n");
  for (const char* engine : {"batch", "jit"}) {
    for (const Program* program : {&dynamic, &mova}) {
      const Result<std::unique_ptr<Engine>> made = MakeEngine(engine, *program, ConstantBank(kBankSize), {});
      EXPECT_TRUE(made.ok()) << made.message();
    }
  }
}

TEST(StaticFlow, AnUnrollingPastTheBoundIsRefusedAndLaterOnesReturnTheError) {
  const Program program = Assemble(
      "vs_2_0\ndcl_position v0\nmov r0, v0\nrep i0\nrep i0\nadd r0, r0, c1\nadd r0, r0, c2\nendrep\nendrep\n"
      "mov oPos, r0\n");
  ConstantBank bank(kBankSize);
  bank.integer(0) = {255, 0, 0, 0};  // 255 * 255 * 2 instructions
  Result<std::unique_ptr<Engine>> made = MakeEngine("batch", program, bank, {});
  ASSERT_FALSE(made.ok());
  EXPECT_NE(made.message().find("more than 4096 instructions"), std::string::npos) << made.message();
  bank.integer(0) = {2, 0, 0, 0};
  std::unique_ptr<Engine> engine = MakeEngine("batch", program, bank, {}).value();
  const std::vector<int> registers = {0};
  const VertexArrays inputs = MakeInputArrays(1, registers);
  VertexArrays outputs = MakeOutputArrays(1, program);
  ASSERT_EQ(engine->Run(inputs, outputs).message(), "");
  bank.integer(0) = {255, 0, 0, 0};
  const Status set = engine->SetConstants(bank);
  ASSERT_FALSE(set.ok());
  EXPECT_EQ(set.error().code, DiagnosticCode::kEngineUnavailable);
  EXPECT_NE(set.message().find("more than 4096 instructions"), std::string::npos) << set.message();
  // Every Run until constants that specialise returns the same error and writes NaN.
  for (int run = 0; run < 2; ++run) {
    const Status ran = engine->Run(inputs, outputs);
    ASSERT_FALSE(ran.ok());
    EXPECT_EQ(ran.error().code, DiagnosticCode::kEngineUnavailable);
    EXPECT_EQ(ran.message(), set.message());
    EXPECT_TRUE(std::isnan(outputs.lane(static_cast<int>(OutputSlot::kPosition), 0)[0]));
  }
  bank.integer(0) = {2, 0, 0, 0};
  ASSERT_EQ(engine->SetConstants(bank).message(), "");
  ASSERT_EQ(engine->Run(inputs, outputs).message(), "");
  EXPECT_FALSE(std::isnan(outputs.lane(static_cast<int>(OutputSlot::kPosition), 0)[0]));
}

}  // namespace
}  // namespace vs11
