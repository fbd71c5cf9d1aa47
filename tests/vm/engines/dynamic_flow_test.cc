// The batch and jit engines on later-model programs with dynamic flow control (vm/core/static_flow.h's
// execution masks): random vs_2_x programs with setp, predicated writes (per-lane p0 swizzles, `!p0`),
// if_comp and if p0 nested in loops, break_comp/breakp/break out of nested loops, callnz p0, branches
// that neighbouring vertices take differently, loops every vertex leaves early and loops that run zero
// times, run by ref, batch and jit on every instruction set the CPU has under both float rules, over a
// vertex count that is no multiple of any vector width, compared bit for bit. Plus hand-computed cases.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "tests/vm/engines/later_model_comparison.h"

namespace vs11 {
namespace {

using namespace later_model;  // NOLINT(build/namespaces): the shared comparison of these tests

constexpr int kBankSize = 256;

// A random vs_2_x program with vs_1_1 arithmetic and every kind of dynamic flow control.
class ProgramWriter : later_model::Draws {
 public:
  explicit ProgramWriter(unsigned seed) : Draws(seed) {}

  // Drawn again until it fits vs_2_x's 256 instruction slots with room to spare.
  std::string Write() {
    std::string text;
    do text = Draw(); while (std::count(text.begin(), text.end(), '\n') > 110);
    return text;
  }

 private:
  std::string Draw() {
    std::string text = "vs_2_x\n";
    for (int i = 0; i < 4; ++i) {
      // Counts 0-4 (0: the loop runs zero times), aL from -2, steps -1 to 2.
      text += fmt::format("defi i{}, {}, {}, {}, 0\n", i, Pick(0, 4), Pick(-2, 6), Pick(-1, 2));
      text += fmt::format("defb b{}, {}\n", i, Pick(0, 1) ? "true" : "false");
    }
    text += "dcl_position v0\ndcl_normal v1\nmov r0, v0\nmov r1, v1\nmov r2, c1\nmov r3, c2\nsetp_gt p0, v0, r1.yzwx\n";
    text += Block(0, 0, false, true);
    text += "mov oPos, r0\nmov oD0, r1\nmov oT0, r2\nmov oT1, r3\nret\nlabel l0\n" + Block(0, 0, false, false) +
            "ret\nlabel l1\n" + Block(0, 0, false, false) + "ret\n";
    return text;
  }

  std::string Lane() { return std::string(1, "xyzw"[Pick(0, 3)]); }
  std::string Register(bool in_loop, Reads& reads) { return Draws::Register(in_loop, reads, 7, 4); }
  std::string Source(bool in_loop, Reads& reads) {
    const bool negate = Pick(0, 3) == 0;
    return (negate ? "-" : "") + Register(in_loop, reads) + SwizzleSuffix();
  }
  // One lane of a source, as if_comp and break_comp read it.
  std::string Scalar(bool in_loop, Reads& reads) {
    const bool negate = Pick(0, 3) == 0;
    return (negate ? "-" : "") + Register(in_loop, reads) + "." + Lane();
  }
  // The two operands of if_comp and break_comp.
  std::string Scalars(bool in_loop) {
    Reads reads;
    const std::string first = Scalar(in_loop, reads);
    return first + ", " + Scalar(in_loop, reads);
  }
  std::string Comparison() {
    static constexpr const char* kNames[] = {"gt", "eq", "ge", "lt", "ne", "le"};
    return kNames[Pick(0, 5)];
  }
  std::string Predicate() { return fmt::format("{}p0.{}", Pick(0, 1) ? "!" : "", Lane()); }
  std::string Destination() {
    static constexpr const char* kMasks[] = {"", ".x", ".yw", ".xyz", ".z"};
    if (Pick(0, 7) == 0) return fmt::format("oT{}{}", Pick(2, 3), kMasks[Pick(0, 4)]);  // written under a mask only
    return Temp() + kMasks[Pick(0, 4)];
  }
  std::string Arithmetic(bool in_loop) {
    static constexpr const char* kTwo[] = {"add", "mul", "dp3", "dp4", "min", "max", "slt", "sge"};
    std::string prefix;
    if (Pick(0, 2) == 0) {  // a predicated write, per lane of p0
      // .xyzw or one lane: the validator's rule (vm/asm/validator_models.cc)
      static constexpr const char* kPredicateSwizzles[] = {".x", ".y", ".z", ".w", "", ".xyzw"};
      prefix = fmt::format("({}p0{}) ", Pick(0, 1) ? "!" : "", kPredicateSwizzles[Pick(0, 5)]);
    }
    Reads reads;
    const auto source = [&] { return Source(in_loop, reads); };
    switch (Pick(0, 4)) {
      case 0: {
        const std::string dest = Destination(), s0 = source(), s1 = source(), s2 = source();
        return prefix + fmt::format("mad {}, {}, {}, {}\n", dest, s0, s1, s2);
      }
      case 1: {
        const std::string dest = Destination();
        return prefix + fmt::format("mov {}, {}\n", dest, source());
      }
      case 2: return prefix + fmt::format("m4x3 {}, {}, c{}\n", Temp(), Temp(), Pick(0, 5));
      case 3: {
        const std::string comparison = Comparison(), lanes = Pick(0, 1) ? "" : "." + Lane(), s0 = source(), s1 = source();
        return fmt::format("setp_{} p0{}, {}, {}\n", comparison, lanes, s0, s1);
      }
      default: {
        const std::string op = kTwo[Pick(0, 7)], dest = Destination(), s0 = source(), s1 = source();
        return prefix + fmt::format("{} {}, {}, {}\n", op, dest, s0, s1);
      }
    }
  }
  std::string Branch(int depth, int loops, bool in_loop, bool main) {
    return Block(depth + 1, loops, in_loop, main) + (Pick(0, 1) ? "else\n" + Block(depth + 1, loops, in_loop, main) : "") + "endif\n";
  }
  // Statements at nesting `depth` (`loops` rep/loop blocks around, `in_loop`: a loop with aL among them),
  // calls and loops with aL only in the main program (the validator keeps aL out of subroutines).
  std::string Block(int depth, int loops, bool in_loop, bool main) {
    std::string text;
    for (int n = Pick(1, 4); n > 0; --n) {
      const int kind = depth < 3 ? Pick(0, 13) : Pick(0, 3);
      if (kind <= 3) {
        text += Arithmetic(in_loop);
      } else if (kind == 4) {
        text += fmt::format("rep i{}\n", Pick(0, 3)) + Block(depth + 1, loops + 1, in_loop, main) + "endrep\n";
      } else if (kind == 5 && main) {
        text += fmt::format("loop aL, i{}\n", Pick(0, 3)) + Block(depth + 1, loops + 1, true, main) + "endloop\n";
      } else if (kind == 6 || kind == 7) {
        text += fmt::format("if_{} {}\n", Comparison(), Scalars(in_loop)) + Branch(depth, loops, in_loop, main);
      } else if (kind == 8) {
        text += "if " + Predicate() + "\n" + Branch(depth, loops, in_loop, main);
      } else if (kind == 9 && loops > 0) {
        text += fmt::format("break_{} {}\n", Comparison(), Scalars(in_loop));
      } else if (kind == 10 && loops > 0) {
        text += "breakp " + Predicate() + "\n";
      } else if (kind == 11 && loops > 0) {  // a break some vertices reach
        text += fmt::format("if_{} {}\n{}break\nendif\n", Comparison(), Scalars(in_loop), Arithmetic(in_loop));
      } else if (kind == 12 && main) {
        text += Pick(0, 1) ? "callnz l1, " + Predicate() + "\n" : fmt::format("callnz l0, {}b{}\n", Pick(0, 1) ? "!" : "", Pick(0, 3));
      } else if (kind == 13) {
        text += fmt::format("if {}b{}\n", Pick(0, 1) ? "!" : "", Pick(0, 3)) + Branch(depth, loops, in_loop, main);
      } else {
        text += Arithmetic(in_loop);
      }
    }
    return text;
  }
};

// Values from a small set, so that eq, ne, ge and le hold for some vertices and not for their
// neighbours; a NaN and a -0 among the constants.
float SmallValue(std::mt19937& random) {
  return static_cast<float>(std::uniform_int_distribution<int>(-4, 4)(random)) * 0.5f;
}

ConstantBank RandomBank(std::mt19937& random) {
  ConstantBank bank(kBankSize);
  for (int k = 0; k < kBankSize; ++k) bank[k] = {SmallValue(random), SmallValue(random), SmallValue(random), SmallValue(random)};
  bank[5][1] = std::numeric_limits<float>::quiet_NaN();
  bank[6][2] = -0.0f;
  return bank;
}

// Runs `source` on ref and every candidate; the differences found, one line each.
std::string Compare(const std::string& source, std::mt19937& random, std::size_t vertices, int* ran = nullptr) {
  const Program program = Assemble(source);
  if (program.instructions.empty()) return "does not assemble";
  const ConstantBank bank = RandomBank(random);
  const VertexArrays inputs = RandomInputs(vertices, [&] { return SmallValue(random); });
  std::string differences;
  for (FloatRules rules : kAllFloatRules) {
    const VertexArrays expected = RunOn("ref", program, bank, inputs, {.float_rules = rules});
    for (const Candidate& candidate : Candidates(rules)) {
      if (Result<std::unique_ptr<Engine>> made = MakeEngine(candidate.engine, program, bank, candidate.options); !made) {
        // Only the unrolled length may stop a program of this writer.
        if (made.message().find("unrolled") == std::string::npos) differences += made.message() + "\n";
        continue;
      }
      if (ran != nullptr) ++*ran;
      const std::string difference = Difference(expected, RunOn(candidate.engine, program, bank, inputs, candidate.options));
      if (!difference.empty()) differences += fmt::format("{}, {}: {}\n", candidate.name, kFloatRulesNames.Name(rules), difference);
    }
  }
  return differences;
}

TEST(DynamicFlow, RandomProgramsMatchTheReferenceBitForBit) {
  const char* env = std::getenv("VS11_DYNAMIC_FLOW_PROGRAMS");
  const int programs = env != nullptr ? std::atoi(env) : 80;
  std::mt19937 random(33);
  int ran = 0;
  for (int p = 0; p < programs; ++p) {
    const std::string source = ProgramWriter(static_cast<unsigned>(p)).Write();
    // 37 vertices: no multiple of 8 or 16; every 8th program 300, a whole batch of 256 and a short one.
    EXPECT_EQ(Compare(source, random, p % 8 == 0 ? 300 : 37, &ran), "") << "program " << p << ":\n" << source;
  }
  EXPECT_GT(ran, programs);  // most programs ran on batch and jit
}

// Neighbouring vertices take different sides of an if, every vertex leaves a loop at a different
// iteration, all leave at the first, zero-trip loops, a break from the inner of two loops, callnz p0.
TEST(DynamicFlow, CornersMatchTheReference) {
  const char* const kPrograms[] = {
      // alternating sides, nested
      ("vs_2_x\ndcl_position v0\nmov r0, v0\nif_gt v0.x, c0.x\nadd r0, r0, c1\nif_lt v0.y, c0.y\nmul r0, r0, c2\n"
       "else\nmov r0.y, c3.x\nendif\nelse\nadd r0, r0, -c1\nendif\nmov oPos, r0\n"),
      // every vertex leaves at its own iteration, counted in r1
      ("vs_2_x\ndefi i0, 40, 0, 1, 0\ndcl_position v0\nmov r0, v0\nmov r1, c0\nrep i0\nbreak_ge r1.x, v0.x\n"
       "add r1, r1, c1\nendrep\nmov oPos, r1\n"),
      // all leave at once (at loop level: the loop ends for everyone) and a zero-trip loop
      ("vs_2_x\ndefi i0, 5, 0, 1, 0\ndefi i1, 0, 0, 1, 0\ndcl_position v0\nmov r0, v0\nrep i0\nadd r0, r0, c1\n"
       "break\nendrep\nrep i1\nmov r0, c2\nendrep\nmov oPos, r0\n"),
      // breakp from the inner of two loops; the outer goes on
      ("vs_2_x\ndefi i0, 3, 0, 1, 0\ndefi i1, 4, 0, 1, 0\ndcl_position v0\nmov r0, c0\nrep i0\nrep i1\n"
       "setp_lt p0.x, r0.x, v0.x\nbreakp !p0.x\nadd r0, r0, c1\nendrep\nadd r0.y, r0.y, c1.y\nendrep\nmov oPos, r0\n"),
      // callnz p0 from a loop, predicated writes to an output only some vertices make
      ("vs_2_x\ndefi i0, 3, 0, 1, 0\ndcl_position v0\nmov r0, v0\nsetp_ge p0, v0, c0\nloop aL, i0\n"
       "callnz l0, p0.y\n(!p0.z) add oT0, r0, c[aL + 1]\nendloop\nmov oPos, r0\nret\nlabel l0\nadd r0, r0, c2\n"
       "setp_ne p0.y, r0.y, c3.y\nret\n"),
      // vs_3_0: o[aL] written under a per-vertex condition, a declared output only some vertices write
      ("vs_3_0\ndefi i0, 2, 0, 1, 0\ndcl_position v0\ndcl_position o0\ndcl_texcoord0 o1\ndcl_texcoord1 o2\n"
       "dcl_color o3\nmov o0, v0\nloop aL, i0\nif_lt v0.x, c[aL + 1].y\nadd o1[aL], v0, c[aL + 3]\nendif\nendloop\n"
       "setp_ge p0, v0, c0\n(!p0.w) mov o3, v0.yxzw\n"),
  };
  std::mt19937 random(7);
  for (const char* source : kPrograms) EXPECT_EQ(Compare(source, random, 45), "") << source;
}

// Values worked out by hand: vertex i has v0.x = i; c0 = (2, 0, 0, 0), c1 = (1, 1, 1, 1).
TEST(DynamicFlow, HandComputedValues) {
  const Program program = Assemble(
      "vs_2_x\ndefi i0, 10, 0, 1, 0\ndcl_position v0\nmov r0, c1\nif_gt v0.x, c0.x\nmov r0.x, -c1.x\nendif\n"
      "mov r1, v0\nrep i0\nbreak_le r1.x, c1.y\nadd r1.x, r1.x, -c1.x\nadd r0.y, r0.y, c1.x\nendrep\n"
      "setp_eq p0.xz, v0.x, c0.x\n(p0.x) mov r0.z, c0.x\n(!p0.z) mov r0.w, c0.y\nmov oPos, r0\n");
  ConstantBank bank(kBankSize);
  bank[0] = {2, 0, 0, 0};
  bank[1] = {1, 1, 1, 1};
  const std::vector<int> registers = {0};
  VertexArrays inputs = MakeInputArrays(9, registers);
  for (std::size_t i = 0; i < 9; ++i) inputs.lane(0, 0)[i] = static_cast<float>(i);
  for (int c = 1; c < 4; ++c) inputs.FillUniform(0, c, 0.0f);
  for (const Candidate& candidate : Candidates(FloatRules::kD3d9)) {
    const VertexArrays out = RunOn(candidate.engine, program, bank, inputs, candidate.options);
    for (std::size_t i = 0; i < 9; ++i) {
      const float x = static_cast<float>(i);
      const float* position[4];
      for (int c = 0; c < 4; ++c) position[c] = out.lane(static_cast<int>(OutputSlot::kPosition), c);
      EXPECT_EQ(position[0][i], x > 2 ? -1.0f : 1.0f) << candidate.name << " vertex " << i;
      EXPECT_EQ(position[1][i], 1.0f + std::max(0.0f, x - 1.0f)) << candidate.name << " vertex " << i;  // its iterations
      EXPECT_EQ(position[2][i], x == 2 ? 2.0f : 1.0f) << candidate.name << " vertex " << i;
      EXPECT_EQ(position[3][i], x == 2 ? 1.0f : 0.0f) << candidate.name << " vertex " << i;
    }
  }
}

}  // namespace
}  // namespace vs11
