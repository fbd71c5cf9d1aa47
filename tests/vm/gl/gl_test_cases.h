// What both gl test files (the gl engine's and the translation's on llvmpipe) run: ordinary inputs
// and constants, and the case each runs under each float rule, an infinite constant times a zero lane
// in every instruction that multiplies (tests/vm/engines/float_rules_test.cc pins its bits on every
// CPU engine); and the opcodes of a program, for their messages.
#pragma once

#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <random>
#include <set>
#include <string>

#include "tests/vm/engines/random_program.h"
#include "vm/asm/assembler.h"
#include "vm/core/machine.h"
#include "vm/core/program.h"

namespace vs11::gl_test {

// Ordinary values: what an application gives a program. Every input lane and constant in [-4, 4].
inline float Ordinary(std::mt19937& rng) { return std::uniform_real_distribution<float>(-4.0f, 4.0f)(rng); }

inline VertexArrays OrdinaryInputs(std::size_t count, std::mt19937& rng) {
  VertexArrays inputs = MakeInputArrays(count, random_program::kInputs);
  for (int reg : random_program::kInputs) {
    for (int c = 0; c < 4; ++c) {
      for (std::size_t i = 0; i < count; ++i) inputs.lane(reg, c)[i] = Ordinary(rng);
    }
  }
  return inputs;
}

inline ConstantBank OrdinaryConstants(std::mt19937& rng) {
  ConstantBank bank;
  for (int reg = 0; reg < bank.size(); ++reg) {
    for (int c = 0; c < 4; ++c) bank[reg][c] = Ordinary(rng);
  }
  return bank;
}

// The program's executable mnemonics, for messages.
inline std::string Opcodes(const Program& program) {
  std::set<std::string> names;
  for (const Instruction& instruction : program.instructions) {
    if (instruction.info().is_executable()) names.insert(std::string(instruction.info().mnemonic));
  }
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : " ") + name;
  return text;
}

struct InfinityTimesZero {
  AssembleResult assembled;
  ConstantBank bank;
  VertexArrays inputs;
};

inline InfinityTimesZero MakeInfinityTimesZero() {
  AssembleOptions assemble;
  assemble.require_position = false;
  InfinityTimesZero test{
      AssembleSource("vs.1.1\nmul oD0, c0, v0\nmov r0, v2\nmad oD1, c0, v0, r0\ndp3 oT0, c0, v0\ndp4 oT1, c0, v0\n"
                     "m4x4 oT2, v0, c2\nm4x3 oT3.xyz, v0, c2\nm3x4 oT4, v0, c2\nm3x3 oT5.xyz, v0, c2\n"
                     "m3x2 oT6.xy, v0, c2\ndst oT7, c0, v0\nlit oPos, v1\n",
                     "infinity_times_zero.vsh", assemble),
      ConstantBank(), VertexArrays()};
  const float inf = INFINITY;
  test.bank[0] = {inf, -inf, -inf, std::bit_cast<float>(std::uint32_t{0x7FC00000u})};
  for (int row = 2; row <= 5; ++row) test.bank[row] = {inf, -inf, inf, -inf};
  const int registers[] = {0, 1, 2};
  test.inputs = MakeInputArrays(1, registers);
  const Vec4f v0 = {0.0f, -0.0f, 0.0f, 0.0f}, v1 = {1.0f, inf, 0.0f, 0.0f}, v2 = {1.0f, 2.0f, 3.0f, 4.0f};
  for (int c = 0; c < 4; ++c) {
    test.inputs.lane(0, c)[0] = v0[c];
    test.inputs.lane(1, c)[0] = v1[c];
    test.inputs.lane(2, c)[0] = v2[c];
  }
  return test;
}

}  // namespace vs11::gl_test
