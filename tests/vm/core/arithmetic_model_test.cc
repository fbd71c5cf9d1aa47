// The reference engine against an independent model of each instruction's arithmetic
// (tests/vm/core/arithmetic_model.h, written from the spec, not from vm/core/semantics.h), for every opcode of
// vm/core/isa.h's table: over a grid of special values and over random operands. The engines are equal to
// the reference bit for bit (engine_differential_test.cc), so this checks all of them.
#include <bit>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/vm/core/arithmetic_model.h"
#include "vm/engines/reference_engine.h"

namespace vs11 {
namespace {

// Special values from the spec's special cases: signed zeros, denormals, the float limits,
// infinities, quiet and signalling NaNs with and without payloads, rcp/rsq's 1, lit's power clamp,
// the ends of exp's range, a0's limit, and values next to integers (floor, frc).
const std::vector<float>& Grid() {
  static const std::vector<float> values = {
      0.0f, -0.0f, 1.0f, -1.0f, 0.5f, -0.25f, 2.5f, -2.5f, 3.0f, 4.0f, 1e-30f, -1e-30f,
      std::ldexp(1.0f, -140), -std::ldexp(1.0f, -149), FLT_MIN, -FLT_MIN, FLT_MAX, -FLT_MAX,
      std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity(),
      std::bit_cast<float>(0x7FC00000u), std::bit_cast<float>(0xFFC00000u), std::bit_cast<float>(0x7FC12345u),
      std::bit_cast<float>(0x7F800001u), std::bit_cast<float>(0xFF812345u), std::bit_cast<float>(0x42FFFE01u),
      -std::bit_cast<float>(0x42FFFE01u), 128.0f, 127.99f, -150.0f, -149.5f, -126.0f, 0.99999994f, 1.00000012f,
      1e30f, 1048576.0f, -1048576.5f, 16777216.0f};
  return values;
}

WriteMask FullestLegalMask(MaskRule rule) {
  switch (rule) {
    case MaskRule::kYOrXy:
    case MaskRule::kXy: return WriteMask(0x3);
    case MaskRule::kXyz: return WriteMask(0x7);
    case MaskRule::kAny:
    case MaskRule::kXyzw:
    case MaskRule::kFull: break;
  }
  return WriteMask(0xF);
}

// `opcode oT0.<fullest mask>, v0, v1, v2` (as many sources as it has; a matrix reads v1..v4).
Program OneInstruction(const OpcodeInfo& info) {
  Instruction instruction;
  instruction.opcode = info.opcode;
  instruction.dest = {{RegisterFile::kTexCoordOut, 0, false}, FullestLegalMask(info.mask_rule)};
  for (int s = 0; s < info.source_count(); ++s) instruction.sources[s].reg = {RegisterFile::kInput, s, false};
  Program program;
  program.instructions.push_back(instruction);
  return program;
}

// How the engine fared on one opcode.
struct Tally {
  long cases = 0;
  long approximate_lanes = 0;  // lanes checked against a precision bound
  long unspecified_lanes = 0;  // lanes the spec leaves open
  double worst_fraction = 0;   // largest error of an approximate lane, as a fraction of its bound
  int failures = 0;
};

std::string Describe(const model::Operands& operands, int count) {
  std::ostringstream text;
  text << std::hexfloat;
  for (int r = 0; r < count; ++r) {
    text << " v" << r << "=(";
    for (int c = 0; c < 4; ++c) text << (c ? ", " : "") << operands[r][c];
    text << ")";
  }
  return text.str();
}

void CheckCase(const OpcodeInfo& info, const Program& program, const model::Operands& operands, Tally& tally) {
  const std::optional<model::Result> expected = model::Model(info.opcode, operands);
  ASSERT_TRUE(expected) << info.mnemonic << " computes a result but the model has none for it";
  VertexState state;
  state.inputs.fill(kDefaultInput);
  for (int r = 0; r < static_cast<int>(operands.size()); ++r) state.inputs[r] = operands[r];
  RunVertex(program, ConstantBank(), state);
  const Vec4f& actual = state.outputs[static_cast<int>(OutputSlot::kTexCoord0)];
  const WriteMask mask = program.instructions[0].dest.mask;
  ++tally.cases;
  for (int lane = 0; lane < 4; ++lane) {
    if (!mask.has(lane)) continue;
    const model::Expected& want = (*expected)[lane];
    ASSERT_NE(want.kind, model::Expected::Kind::kUnwritten)
        << info.mnemonic << " writes lane " << lane << " but the model says it does not";
    tally.unspecified_lanes += want.kind == model::Expected::Kind::kUnspecified;
    if (want.kind == model::Expected::Kind::kWithin) {
      ++tally.approximate_lanes;
      tally.worst_fraction = std::max(tally.worst_fraction, model::ErrorFraction(want, actual[lane]));
    }
    std::string why;
    if (model::Accepts(want, actual[lane], why)) continue;
    if (++tally.failures <= 10) {
      ADD_FAILURE() << info.mnemonic << " lane " << "xyzw"[lane] << ": " << why << "\n  operands:"
                    << Describe(operands, info.kind == ResultKind::kMatrix ? 5 : info.source_count());
    }
  }
}

// Runs `make_operands(k)` for k < cases through every opcode with arithmetic, and prints a line per opcode.
void CheckEveryOpcode(const char* label, int cases, const std::function<model::Operands(int)>& make_operands) {
  for (const OpcodeInfo& info : kOpcodeTable) {
    if (info.since != ShaderModel::kVs11) continue;  // the machine the engines run
    if (info.kind == ResultKind::kNoResult) {
      EXPECT_FALSE(model::Model(info.opcode, model::Operands{})) << info.mnemonic;
      continue;
    }
    const Program program = OneInstruction(info);
    Tally tally;
    for (int k = 0; k < cases && tally.failures == 0; ++k) {
      CheckCase(info, program, make_operands(k), tally);
      if (::testing::Test::HasFatalFailure()) return;
    }
    std::printf("[ model ] %-5s %s: %ld cases, %ld lanes within a precision bound (worst %.3g of it), %ld left "
                "open by the spec%s\n",
                std::string(info.mnemonic).c_str(), label, tally.cases, tally.approximate_lanes, tally.worst_fraction,
                tally.unspecified_lanes, tally.failures ? ", FAILED" : "");
  }
}

TEST(ArithmeticModel, EveryOpcodeOverTheSpecialValueGrid) {
  const std::vector<float>& g = Grid();
  const int n = static_cast<int>(g.size());
  // Case k = u + n v: every pair of grid values meets in (a.x, a.y), (a.x, b.x), (a.y, b.y), (a.y, a.w)
  // (lit's base and power) and (a.w, b.w); the other lanes and s2 mix them further.
  CheckEveryOpcode("grid", n * n, [&](int k) {
    const int u = k % n, v = k / n;
    const auto at = [&](int i) { return g[static_cast<std::size_t>(i % n)]; };
    model::Operands operands;
    operands[0] = {at(u), at(v), at(u + v), at(u + 2 * v + 1)};
    operands[1] = {at(v), at(u), at(3 * u + v), at(u + 2 * v + 1 + v)};
    operands[2] = {at(u + v), at(2 * u + 1), at(v + 5), at(u + 7)};
    operands[3] = {at(2 * v), at(u + 3), at(v + 11), at(u * v)};
    operands[4] = {at(u + 13), at(v * 3), at(u + v + 17), at(2 * u + v)};
    return operands;
  });
}

// Mostly ordinary values, across the whole exponent range (exp, expp, log, lit reach their limits),
// with random bit patterns, values next to integers and grid values mixed in.
class RandomOperands {
 public:
  float Value() {
    switch (std::uniform_int_distribution<int>(0, 9)(rng_)) {
      case 0: return std::bit_cast<float>(static_cast<std::uint32_t>(rng_()));
      case 1: return Grid()[std::uniform_int_distribution<std::size_t>(0, Grid().size() - 1)(rng_)];
      case 2: {
        const float whole = static_cast<float>(std::uniform_int_distribution<int>(-160, 160)(rng_));
        return whole + std::uniform_int_distribution<int>(-1, 1)(rng_) * std::ldexp(1.0f, -16);
      }
      case 3:
      case 4: {
        const float magnitude = std::ldexp(std::uniform_real_distribution<float>(1.0f, 2.0f)(rng_),
                                           std::uniform_int_distribution<int>(-149, 127)(rng_));
        return rng_() % 2 ? magnitude : -magnitude;
      }
      case 5: return std::uniform_real_distribution<float>(-160.0f, 160.0f)(rng_);
      default: return std::uniform_real_distribution<float>(-4.0f, 4.0f)(rng_);
    }
  }
  model::Operands Operands() {
    model::Operands operands;
    for (auto& reg : operands) {
      for (float& lane : reg) lane = Value();
    }
    return operands;
  }

 private:
  std::mt19937 rng_{20261123};
};

TEST(ArithmeticModel, EveryOpcodeOverRandomOperands) {
  RandomOperands random;
  CheckEveryOpcode("random", 40000, [&](int) { return random.Operands(); });
}

}  // namespace
}  // namespace vs11
