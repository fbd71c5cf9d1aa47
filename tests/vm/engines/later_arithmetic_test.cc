// The later models' arithmetic on the batch and jit engines: random vs_2_x and vs_3_0 programs that use
// abs, crs, lrp, nrm, pow, sgn, sincos and mova, _sat on destinations, _abs on sources (vs_3_0),
// relative reads by every lane of a0 and temporaries up to r31, with inputs and constants that hold
// the edge values (signed zeros, denormals, infinities, NaN, mova's ties 2.5 and -2.5, pow of 0 and
// of negatives, nrm of a zero vector), run by ref, batch (at every Highway target the CPU has) and jit
// (at every instruction set) under both float rules and compared bit for bit.
#include <cfloat>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "hwy/highway.h"
#include "hwy/tests/hwy_gtest.h"
#include "tests/vm/engines/later_model_comparison.h"
#include "vm/asm/assembler.h"

namespace vs11 {
namespace {

constexpr int kBankSize = 256;
constexpr int kTemps = 32;

std::optional<std::string> NoFiles(const std::filesystem::path&) { return std::nullopt; }

// Not validated: the engines must agree on what a token stream the validator refuses does too (lanes
// crs or sincos leave unwritten read 0, nrm into its own source), as on a driver that skips validation.
Program Assemble(const std::string& source) {
  AssembleOptions options;
  options.validate = false;
  const AssembleResult assembled = AssembleSource(source, "later.vsh", options, NoFiles);
  EXPECT_TRUE(assembled.program) << assembled.diagnostics.ToString() << "\n" << source;
  return assembled.program ? *assembled.program : Program{};
}

// Values the arithmetic treats specially, and ordinary ones around them.
const std::vector<float>& EdgeValues() {
  static const std::vector<float> values = {
      0.0f, -0.0f, 1.0f, -1.0f, 0.5f, -0.5f, 2.5f, -2.5f, 1.5f, -1.5f, 0.49999997f, 3.0f, -4.0f, 0.25f,
      std::ldexp(1.0f, -130) /* denormal */, -std::ldexp(1.0f, -149), FLT_MIN, FLT_MAX, -FLT_MAX, 1e30f, -1e-30f,
      std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity(),
      std::numeric_limits<float>::quiet_NaN(), 100.0f, -200.0f};
  return values;
}

class Values {
 public:
  explicit Values(unsigned seed) : random_(seed) {}
  // A third edge values, the rest ordinary; some small integers, which mova makes addresses of.
  float Next() {
    const int kind = Pick(0, 8);
    if (kind < 3) return EdgeValues()[static_cast<std::size_t>(Pick(0, static_cast<int>(EdgeValues().size()) - 1))];
    if (kind == 3) return static_cast<float>(Pick(-3, 40));
    return std::uniform_real_distribution<float>(-3.0f, 3.0f)(random_);
  }
  int Pick(int low, int high) { return std::uniform_int_distribution<int>(low, high)(random_); }

 private:
  std::mt19937 random_;
};

// A random program of `model` (vs_2_x or vs_3_0): every temporary set from the inputs, a0 set by mova
// before the body, then arithmetic of every later row and vs_1_1's kernel families with the
// modifiers, and the last temporaries written copied to the outputs.
class LaterProgramWriter {
 public:
  LaterProgramWriter(unsigned seed, std::string_view model) : values_(seed), vs30_(model == "vs_3_0"), model_(model) {}

  std::string Write() {
    std::string text = fmt::format("{}\ndcl_position v0\ndcl_normal v1\ndcl_texcoord v2\n", model_);
    if (vs30_) {
      text += "dcl_position o0\ndcl_color o1\ndcl_color1 o2\n";
      for (int t = 0; t < 8; ++t) text += fmt::format("dcl_texcoord{} o{}\n", t, 3 + t);
    }
    if (values_.Pick(0, 2) == 0) text += "rep i0\n";  // sometimes inside static flow, unrolled twice
    const bool in_rep = text.ends_with("rep i0\n");
    text += fmt::format("mova a0, v2{}\n", Swizzle());
    for (int r = 0; r < kTemps; ++r) text += fmt::format("mov r{}, v{}{}\n", r, values_.Pick(0, 2), Swizzle());
    for (int n = values_.Pick(8, 30); n > 0; --n) text += Instruction();
    if (in_rep) text += "endrep\n";
    const char* outputs[] = {"oPos", "oD0", "oD1", "oT0", "oT1", "oT2", "oT3", "oT4", "oT5", "oT6", "oT7"};
    for (int o = 0; o < 11; ++o) {
      const int temp = written_.empty() ? o : written_[written_.size() - 1 - o % written_.size()];
      text += fmt::format("mov {}, r{}\n", vs30_ ? fmt::format("o{}", o) : outputs[o], temp);
    }
    return text;
  }

  static std::string Prelude() { return "defi i0, 2, 0, 1, 0\n"; }

 private:
  std::string Swizzle() {
    static constexpr const char* kSwizzles[] = {"", ".x", ".yzxw", ".wwzy", ".zzzz", ".y", ".w"};
    return kSwizzles[values_.Pick(0, 6)];
  }
  std::string Replicate() { return std::string(".") + "xyzw"[values_.Pick(0, 3)]; }
  std::string Temp() { return fmt::format("r{}", values_.Pick(0, kTemps - 1)); }
  // A register with `modifier` after its name: c5_abs[a0.y] is |c[a0.y + 5]|. A temporary where the
  // instruction already reads a constant or an input (the later models' read ports: one c#, one v#).
  std::string Register(const std::string& modifier) {
    const int kind = values_.Pick(0, 5);
    if (kind <= 1 || (kind == 2 && reads_input_) || (kind >= 3 && reads_constant_)) return Temp() + modifier;
    if (kind == 2) {
      reads_input_ = true;
      return fmt::format("v{}{}", values_.Pick(0, 2), modifier);
    }
    reads_constant_ = true;
    if (kind == 3) return fmt::format("c{}{}", values_.Pick(0, kBankSize - 1), modifier);
    return fmt::format("c{}{}[a0.{}]", values_.Pick(0, 40), modifier, "xyzw"[values_.Pick(0, 3)]);
  }
  // A source: a register, maybe _abs (vs_3_0), maybe negated, swizzled as `swizzle` says.
  std::string Source(const std::string& swizzle) {
    const std::string modifier = vs30_ && values_.Pick(0, 3) == 0 ? "_abs" : "";
    const char* sign = values_.Pick(0, 3) == 0 ? "-" : "";
    return fmt::format("{}{}{}", sign, Register(modifier), swizzle);
  }
  std::string Source() { return Source(Swizzle()); }
  std::string Mask(std::uint8_t allowed) {
    std::uint8_t bits = 0;
    while (bits == 0) bits = static_cast<std::uint8_t>(values_.Pick(1, 15) & allowed);
    if (bits == 0xF && values_.Pick(0, 1) == 0) return "";
    std::string mask = ".";
    for (int c = 0; c < 4; ++c) {
      if (bits & (1 << c)) mask += "xyzw"[c];
    }
    return mask;
  }
  // A temporary destination, remembered for the outputs, maybe _sat; its mask a subset of `allowed`,
  // or all of it when `whole` (a matrix's).
  std::string Dest(std::string_view opcode, std::uint8_t allowed = 0xF, bool whole = false) {
    const int temp = values_.Pick(0, kTemps - 1);
    written_.push_back(temp);
    const std::string sat = values_.Pick(0, 3) == 0 ? "_sat" : "";
    return fmt::format("{}{} r{}{}", opcode, sat, temp, whole ? "" : Mask(allowed));
  }

  // sgn's two scratch registers: two different temporaries.
  std::string ScratchPair() {
    const int first = values_.Pick(0, kTemps - 1);
    const int second = (first + values_.Pick(1, kTemps - 1)) % kTemps;
    return fmt::format("r{}, r{}", first, second);
  }

  std::string Instruction() {
    reads_constant_ = false;
    reads_input_ = false;
    switch (values_.Pick(0, 15)) {
      case 0: return fmt::format("{}, {}\n", Dest("abs"), Source());
      case 1: return fmt::format("{}, {}, {}\n", Dest("crs", 0x7), Source(), Source());
      case 2: return fmt::format("{}, {}, {}, {}\n", Dest("lrp"), Source(), Source(), Source());
      case 3: return fmt::format("{}, {}\n", Dest("nrm"), Source());
      case 4: return fmt::format("{}, {}, {}\n", Dest("pow"), Source(Replicate()), Source(Replicate()));
      case 5: return fmt::format("{}, {}, {}\n", Dest("sgn"), Source(), ScratchPair());
      case 6:
        return vs30_ ? fmt::format("{}, {}\n", Dest("sincos", 0x3), Source(Replicate()))
                     : fmt::format("{}, {}, c250, c251\n", Dest("sincos", 0x3), Source(Replicate()));
      case 7: return fmt::format("mova a0{}, {}\n", Mask(0xF), Source());
      case 8: return fmt::format("{}, {}, {}, {}\n", Dest("mad"), Source(), Source(), Source());
      case 9: return fmt::format("{}, {}, {}\n", Dest("dp4"), Source(), Source());
      case 10: return fmt::format("{}, {}\n", Dest("rcp"), Source(Replicate()));
      case 11:
        reads_constant_ = true;  // the matrix's rows
        return fmt::format("{}, {}, c{}\n", Dest("m4x4", 0xF, true), Source(), values_.Pick(0, 200));
      case 12: return fmt::format("{}, {}\n", Dest("frc"), Source());
      case 13: return fmt::format("{}, {}\n", Dest("lit"), Source());
      default: return fmt::format("{}, {}, {}\n", Dest("add"), Source(), Source());
    }
  }

  Values values_;
  const bool vs30_;
  const std::string model_;
  std::vector<int> written_;
  bool reads_constant_ = false;  // by the instruction being drawn
  bool reads_input_ = false;
};

ConstantBank EdgeBank(Values& values) {
  ConstantBank bank(kBankSize);
  for (int k = 0; k < kBankSize; ++k) bank[k] = {values.Next(), values.Next(), values.Next(), values.Next()};
  return bank;
}

// Every ordered pair of edge values (v0 with v1) once, v2 random edge values.
VertexArrays EdgeInputs(Values& values) {
  const std::vector<float>& edges = EdgeValues();
  const std::size_t n = edges.size();
  const std::vector<int> registers = {0, 1, 2};
  VertexArrays inputs = MakeInputArrays(n * n, registers);
  for (std::size_t i = 0; i < n * n; ++i) {
    for (int c = 0; c < 4; ++c) {
      inputs.lane(0, c)[i] = edges[(i / n + static_cast<std::size_t>(c)) % n];
      inputs.lane(1, c)[i] = edges[(i + static_cast<std::size_t>(c)) % n];
      inputs.lane(2, c)[i] = values.Next();
    }
  }
  return inputs;
}

using later_model::Candidate;
using later_model::Candidates;
using later_model::Difference;
using later_model::RunOn;

// Ref against every candidate on `source`; the number of runs compared.
int ExpectSameAsReference(const std::string& source, Values& values) {
  const Program program = Assemble(source);
  if (program.instructions.empty()) return 0;
  const ConstantBank bank = EdgeBank(values);
  const VertexArrays inputs = EdgeInputs(values);
  int compared = 0;
  for (FloatRules rules : kAllFloatRules) {
    const VertexArrays expected = RunOn("ref", program, bank, inputs, {.float_rules = rules});
    for (const Candidate& candidate : Candidates(rules)) {
      EXPECT_EQ(Difference(expected, RunOn(candidate.engine, program, bank, inputs, candidate.options)), "")
          << candidate.name << ", " << kFloatRulesNames.Name(rules) << ":\n" << source;
      ++compared;
    }
  }
  return compared;
}

// Parameterised by the Highway target the batch engine's kernels run on.
class LaterArithmetic : public hwy::TestWithParamTarget {};
HWY_TARGET_INSTANTIATE_TEST_SUITE_P(LaterArithmetic);

TEST_P(LaterArithmetic, RandomProgramsMatchTheReferenceBitForBit) {
  const char* env = std::getenv("VS11_LATER_ARITHMETIC_PROGRAMS");
  const int programs = env != nullptr ? std::atoi(env) : 40;
  int compared = 0;
  for (int p = 0; p < programs; ++p) {
    const std::string_view model = p % 2 == 0 ? "vs_3_0" : "vs_2_x";
    LaterProgramWriter writer(static_cast<unsigned>(p), model);
    std::string body = writer.Write();
    body.insert(body.find('\n') + 1, LaterProgramWriter::Prelude());
    Values values(1000u + static_cast<unsigned>(p));
    compared += ExpectSameAsReference(body, values);
  }
  EXPECT_GE(compared, programs * 2 * 2);  // batch and at least one jit, both rules
}

// Each later row and modifier alone, on every pair of edge values.
TEST_P(LaterArithmetic, EachRowOnEdgeValuesMatchesTheReference) {
  const char* const kBodies[] = {
      "abs r0, v0\nmov oT0, r0\n",
      "mov r1, v1\ncrs r0.xyz, v0, r1\nmov oT0, r0\n",
      "mov r0, v1\ncrs r0.xz, v0, r0.yzxw\nmov oT0, r0\n",  // w and y left as they were, sources read first
      "mov r1, v1\nmov r2, v2\nlrp r0, v0, r1, r2\nmov oT0, r0\n",
      "nrm r0, v0\nnrm r1, v1.xyzx\nmov oT0, r0\nmov oT1, r1\n",
      "mov r2, v1\npow r0, v0.x, r2.y\npow r1, r2.w, v0.z\nmov oT0, r0\nmov oT1, r1\n",
      "sgn r0, v0, r1, r2\nmov oT0, r0\n",
      "mov r0, v1\nsincos r0.xy, v0.x, c250, c251\nsincos r1.y, v1.z, c250, c251\nmov oT0, r0\nmov oT1, r1\n",
      "mova a0, v0\nmov oT0, c[a0.x + 3]\nmov oT1, c[a0.y + 3]\nmov oT2, c[a0.z + 10]\nmov oT3, c[a0.w + 0]\n",
      "mova a0.yw, v0\nmova a0.x, v1.w\nmov oT0, c[a0.x + 1]\nmov oT1, c[a0.y + 2]\nmov oT2, c[a0.z + 3]\n"
      "m4x4 r0, v2, c[a0.w + 4]\nmov oT3, r0\n",
      "mov_sat r0, v0\nmov r2, v1\nadd_sat r1, v0, r2\nmov oT0, r0\nmov oT1, r1\n",
      "mov r4, v1\ndp4_sat r0.xz, v0, r4\nm4x4_sat r1, v0, c2\nrcp_sat r2.yw, v1.x\nlit_sat r3, v0\n"
      "mov oT0, r0\nmov oT1, r1\nmov oT2, r2\nmov oT3, r3\n",
      "mova a0.y, v0.x\nmova_sat a0.x, v1.y\nmov oT0, c[a0.x + 0]\nmov oT1, c[a0.y + 5]\n",
      "mov r31, v0\nmov r20.xy, v1\nadd r12, r31, r20\nmov oT0, r12\nmov oT1, r20\n",
  };
  const char* const kVs30Bodies[] = {
      "mov r0, -v0_abs\nmov r2, v1\nadd r1, v0_abs, -r2_abs.yxzw\nmov o3, r0\nmov o4, r1\n",
      "mov r4, v1\ndp4 r0, v0_abs, -r4_abs\nm4x4 r1, -v0_abs, c2\nrcp r2, -v1_abs.z\nmova a0, -v0_abs\n"
      "mov r3, -c2_abs[a0.x]\nmov o3, r0\nmov o4, r1\nmov o5, r2\nmov o6, r3\n",
      "mov r3, v1\npow_sat r0, v0_abs.x, -r3.y\nnrm_sat r1, -v0_abs\nsincos_sat r2.xy, v1_abs.w\nmov r2.zw, v0\n"
      "mov o3, r0\nmov o4, r1\nmov o5, r2\n",
  };
  Values values(7);
  int compared = 0;
  for (const char* body : kBodies) {
    compared += ExpectSameAsReference(std::string("vs_2_x\ndcl_position v0\ndcl_normal v1\ndcl_texcoord v2\n"
                                                  "mov oPos, v0\n") + body, values);
  }
  for (const char* body : kVs30Bodies) {
    compared += ExpectSameAsReference(std::string("vs_3_0\ndcl_position v0\ndcl_normal v1\ndcl_texcoord v2\n"
                                                  "dcl_position o0\ndcl_texcoord o3\ndcl_texcoord1 o4\n"
                                                  "dcl_texcoord2 o5\ndcl_texcoord3 o6\nmov o0, v0\n") + body, values);
  }
  EXPECT_GT(compared, 0);
}

}  // namespace
}  // namespace vs11
