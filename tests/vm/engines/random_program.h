// The random vs_1_1 programs, constants and inputs of the engines' differential tests
// (engine_differential_test.cc), shared with the translator's tests (tests/vm/translate/): every
// opcode including the macros, every register file, relative addressing, def, unwritten temporaries,
// and values that mix special ones (signed zeros, denormals, infinities, NaN payloads) with ordinary.
#pragma once

#include <bit>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <random>
#include <span>
#include <vector>

#include "vm/core/isa.h"
#include "vm/core/machine.h"
#include "vm/core/program.h"

namespace vs11::random_program {

inline std::uint32_t Bits(float x) { return std::bit_cast<std::uint32_t>(x); }

// Inputs and outputs the two engines are compared on.
inline constexpr int kInputs[] = {0, 1, 2, 3};  // v4..v15 are absent and read (0, 0, 0, 1)

inline const std::vector<float>& SpecialValues() {
  static const std::vector<float> values = {
      0.0f, -0.0f, 1.0f, -1.0f, 0.5f, -2.5f, std::ldexp(1.0f, -130) /* denormal */, -std::ldexp(1.0f, -149),
      FLT_MIN, FLT_MAX, -FLT_MAX, std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity(),
      std::bit_cast<float>(0x7FC00000u) /* NaN */, std::bit_cast<float>(0xFFC00000u) /* -NaN, x86's default */,
      std::bit_cast<float>(0x7FC12345u) /* NaN with payload */, 1e-30f, 1e30f, 128.0f, 127.99f, -150.0f,
      -149.5f, 0.99999994f, 3.0f};
  return values;
}

// Every ordered pair of `values` in v0 and v1, all four lanes: vertex i holds values[i / n] in v0 and
// values[i % n] in v1 (n values), so a two-operand instruction meets each pair once.
inline VertexArrays EveryPairOf(std::span<const float> values) {
  const std::size_t n = values.size();
  const int registers[] = {0, 1};
  VertexArrays inputs = MakeInputArrays(n * n, registers);
  for (std::size_t i = 0; i < n * n; ++i) {
    for (int c = 0; c < 4; ++c) {
      inputs.lane(0, c)[i] = values[i / n];
      inputs.lane(1, c)[i] = values[i % n];
    }
  }
  return inputs;
}

inline Instruction MakeInstruction(Opcode opcode, DestOperand dest, std::initializer_list<SourceOperand> sources) {
  Instruction instruction;
  instruction.opcode = opcode;
  instruction.dest = dest;
  int s = 0;
  for (const SourceOperand& source : sources) instruction.sources[s++] = source;
  return instruction;
}

constexpr RegisterRef Temp(int index) { return {RegisterFile::kTemp, index, false}; }
constexpr RegisterRef Input(int index) { return {RegisterFile::kInput, index, false}; }
constexpr RegisterRef Const(int index, bool relative = false) { return {RegisterFile::kConst, index, relative}; }
constexpr RegisterRef Output(int slot) {
  return slot < static_cast<int>(OutputSlot::kDiffuse)
             ? RegisterRef{RegisterFile::kRasterOut, slot, false}
             : slot < static_cast<int>(OutputSlot::kTexCoord0)
                   ? RegisterRef{RegisterFile::kAttributeOut, slot - static_cast<int>(OutputSlot::kDiffuse), false}
                   : RegisterRef{RegisterFile::kTexCoordOut, slot - static_cast<int>(OutputSlot::kTexCoord0), false};
}
inline constexpr RegisterRef kAddressRegister = {RegisterFile::kAddress, 0, false};
constexpr SourceOperand Src(RegisterRef reg, Swizzle swizzle = Swizzle(), bool negate = false) {
  return {reg, swizzle, negate};
}

// The masks a random or swept instruction of this opcode may write.
inline std::vector<WriteMask> LegalMasks(const OpcodeInfo& info) {
  switch (info.mask_rule) {
    case MaskRule::kYOrXy: return {WriteMask(0x2), WriteMask(0x3)};
    case MaskRule::kXy: return {WriteMask(0x3)};
    case MaskRule::kXyz: return {WriteMask(0x7)};
    case MaskRule::kXyzw:
    case MaskRule::kFull: return {WriteMask(0xF)};
    case MaskRule::kAny: break;
  }
  std::vector<WriteMask> masks;
  for (std::uint8_t bits = 1; bits <= 0xF; ++bits) masks.push_back(WriteMask(bits));
  return masks;
}

class ProgramGenerator {
 public:
  explicit ProgramGenerator(unsigned seed) : rng_(seed) {}

  // Mostly ordinary values, with special values, random bit patterns (NaN payloads, denormals) and
  // small integers (useful as a0) mixed in.
  float Value() {
    const int kind = Uniform(0, 19);
    if (kind < 3) return SpecialValues()[static_cast<std::size_t>(Uniform(0, static_cast<int>(SpecialValues().size()) - 1))];
    if (kind == 3) return std::bit_cast<float>(static_cast<std::uint32_t>(rng_()));
    if (kind == 4) return static_cast<float>(Uniform(-5, 100));
    return std::uniform_real_distribution<float>(-4.0f, 4.0f)(rng_);
  }

  ConstantBank Constants() {
    ConstantBank bank;
    for (int reg = 0; reg < bank.size(); ++reg) {
      for (int c = 0; c < 4; ++c) bank[reg][c] = Value();
    }
    return bank;
  }

  // Some lanes hold one value throughout (VertexArrays::FillUniform), which the jit compiles in.
  VertexArrays Inputs(std::size_t count) {
    VertexArrays inputs = MakeInputArrays(count, kInputs);
    for (int reg : kInputs) {
      for (int c = 0; c < 4; ++c) {
        if (Chance(12)) {
          inputs.FillUniform(reg, c, Value());
        } else {
          for (std::size_t i = 0; i < count; ++i) inputs.lane(reg, c)[i] = Value();
        }
      }
    }
    return inputs;
  }

  Program MakeProgram() {
    Program program;
    auto& code = program.instructions;
    if (Chance(30)) {  // def constants override the API's
      Instruction def;
      def.opcode = Opcode::kDef;
      def.dest = {Const(Uniform(0, 20)), WriteMask()};
      for (auto& bits : def.def_bits) bits = Bits(Value());
      code.push_back(def);
    }
    // Most temporaries start from inputs; the rest read 0 until written.
    for (int reg = 0; reg < kTempRegisterCount; ++reg) {
      if (Chance(85)) code.push_back(MakeInstruction(Opcode::kMov, {Temp(reg), WriteMask()}, {RandomSource(true)}));
    }
    const int body = Uniform(1, 24);
    for (int k = 0; k < body; ++k) code.push_back(RandomInstruction());
    // Make the temporaries' final values visible.
    for (int reg = 0; reg < kTexCoordOutputCount; ++reg) {
      code.push_back(MakeInstruction(Opcode::kMov, {Output(static_cast<int>(OutputSlot::kTexCoord0) + reg), WriteMask()},
                                     {Src(Temp(reg))}));
    }
    code.push_back(MakeInstruction(Opcode::kMov, {Output(static_cast<int>(OutputSlot::kSpecular)), WriteMask()},
                                   {Src(Temp(8))}));
    return program;
  }

 private:
  int Uniform(int low, int high) { return std::uniform_int_distribution<int>(low, high)(rng_); }
  bool Chance(int percent) { return Uniform(0, 99) < percent; }

  SourceOperand RandomSource(bool input_only = false) {
    SourceOperand source;
    source.swizzle = Chance(40) ? Swizzle() : Swizzle(static_cast<std::uint8_t>(Uniform(0, 255)));
    source.negate = Chance(30);
    const int file = input_only ? 1 : Uniform(0, 9);
    if (file < 5) {
      source.reg = Temp(Uniform(0, kTempRegisterCount - 1));
    } else if (file < 7) {
      source.reg = Input(Chance(90) ? Uniform(0, 3) : Uniform(4, 15));
    } else if (file < 9) {
      source.reg = Const(Uniform(0, kDefaultConstantCount - 1));
    } else {
      source.reg = Const(Uniform(0, 40), true);  // c[a0.x + n]
    }
    return source;
  }

  Instruction RandomInstruction() {
    const OpcodeInfo* info;
    do {
      info = &kOpcodeTable[static_cast<std::size_t>(Uniform(0, kVs11OpcodeCount - 1))];  // vs_1_1's rows
    } while (!info->is_executable());
    Instruction instruction;
    instruction.opcode = info->opcode;
    for (int s = 0; s < info->source_count(); ++s) instruction.sources[s] = RandomSource();
    if (info->kind == ResultKind::kMatrix) instruction.sources[1].swizzle = Swizzle();  // as the validator asks
    const std::vector<WriteMask> masks = LegalMasks(*info);
    WriteMask mask = masks[static_cast<std::size_t>(Uniform(0, static_cast<int>(masks.size()) - 1))];
    if (Chance(3)) mask = WriteMask(static_cast<std::uint8_t>(Uniform(1, 15)));  // unvalidated
    // logp.y turns a NaN's payload into an ordinary number, so a NaN whose bits the engines may
    // choose differently (see NanBits) would surface as a different value: leave logp.y unwritten.
    if (info->opcode == Opcode::kLogp) mask = WriteMask(mask.bits() & 0xD ? mask.bits() & 0xD : 0x1);
    const int dest = Uniform(0, 19);
    if (info->opcode == Opcode::kMov && dest < 3) {
      instruction.dest = {kAddressRegister, WriteMask(0x1)};
    } else if (dest < 6) {
      // oPos, oFog, oPts, oD0: the slots the epilogue leaves alone.
      instruction.dest = {Output(Uniform(0, static_cast<int>(OutputSlot::kDiffuse))), mask};
    } else {
      instruction.dest = {Temp(Uniform(0, kTempRegisterCount - 1)), mask};
    }
    return instruction;
  }

  std::mt19937 rng_;
};

}  // namespace vs11::random_program
