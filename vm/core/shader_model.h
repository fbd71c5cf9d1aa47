// The D3D9 vertex shader models and what each allows: the one place the assembler, validator,
// disassembler and bytecode ask whether an opcode or a register exists in a program's model, and what
// its limits are (vm/core/isa.h's opcode table names each opcode's first model). Every model assembles,
// decodes, disassembles and validates; vs_1_1 runs on every engine, the others on the reference engine
// and, specialised for their i#/b#, on batch, jit and gl (the rest refuse them by name: EngineRefusal in
// vm/core/machine.h).
// Sources: ../shared/spec/vs_1_1.md §1.1, §4.2 (version tokens), §4.6 (register types), §4.7; the
// later models' register counts and limits from the D3D9 reference (D3DVS20CAPS / vs_3_0's fixed
// counts) and the register types and numbers Microsoft's assembler writes (Wine's tests; spec sections
// "vs_2_0", "vs_2_x", "vs_3_0").
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>

namespace vs11 {

// In the order each model adds to the one before: a later model allows everything an earlier one does.
enum class ShaderModel : std::uint8_t { kVs11, kVs20, kVs2x, kVs30 };

struct ShaderModelInfo {
  ShaderModel model;
  std::string_view name;        // as a version statement spells it
  std::uint32_t version_token;  // §4.2: 0xFFFE, major, minor (vs_2_x is minor 1)
  bool enabled;                 // programs of this model assemble, decode and validate
  bool runs;                    // every engine runs programs of this model (the later ones: ref; batch, jit and gl specialised)
  // Instruction slots (vs_3_0: the minimum a device offers), and nesting depths: static flow control
  // (if on b#, call), loop/rep, call, and dynamic flow control (if_comp, predicated if, break_comp).
  // vs_2_x: the maximal D3DVS20CAPS (DynamicFlowControlDepth 24, NumTemps 32, StaticFlowControlDepth 4,
  // predication) and 256 slots.
  int instruction_slots;
  int static_flow_depth;
  int loop_depth;
  int call_depth;
  int dynamic_flow_depth;
};
inline constexpr std::array kShaderModels = {
    ShaderModelInfo{ShaderModel::kVs11, "vs_1_1", 0xFFFE0101, true, true, 128, 0, 0, 0, 0},
    ShaderModelInfo{ShaderModel::kVs20, "vs_2_0", 0xFFFE0200, true, false, 256, 4, 4, 4, 0},
    ShaderModelInfo{ShaderModel::kVs2x, "vs_2_x", 0xFFFE0201, true, false, 256, 4, 4, 4, 24},
    ShaderModelInfo{ShaderModel::kVs30, "vs_3_0", 0xFFFE0300, true, false, 512, 4, 4, 4, 24},
};
inline constexpr int kShaderModelCount = static_cast<int>(kShaderModels.size());
static_assert([] {
  for (int i = 0; i < kShaderModelCount; ++i) {
    if (static_cast<int>(kShaderModels[i].model) != i) return false;
  }
  return true;
}());

constexpr const ShaderModelInfo& Info(ShaderModel model) { return kShaderModels[static_cast<int>(model)]; }
constexpr std::string_view ShaderModelName(ShaderModel model) { return Info(model).name; }

// The model of a version token; vs_1_0 (0xFFFE0100) is vs_1_1's model (§4.2: the same machine).
constexpr std::optional<ShaderModel> ShaderModelOfVersion(std::uint32_t version_token) {
  if (version_token == 0xFFFE0100) return ShaderModel::kVs11;
  for (const ShaderModelInfo& info : kShaderModels) {
    if (info.version_token == version_token) return info.model;
  }
  return std::nullopt;
}

// Whether programs with this version token assemble, decode and run.
constexpr bool VersionEnabled(std::uint32_t version_token) {
  const std::optional<ShaderModel> model = ShaderModelOfVersion(version_token);
  return model && Info(*model).enabled;
}

// D3DSHADER_PARAM_REGISTER_TYPE values (§4.6) of the register files a vertex shader has.
enum class RegisterFile : std::uint8_t {
  kTemp = 0,           // r#
  kInput = 1,          // v#
  kConst = 2,          // c#
  kAddress = 3,        // a0
  kRasterOut = 4,      // oPos (0), oFog (1), oPts (2)
  kAttributeOut = 5,   // oD0, oD1
  kTexCoordOut = 6,    // oT0-oT7 (vs_3_0: o0-o11)
  kConstInt = 7,       // i#, vs_2_0 on
  kSampler = 10,       // s#, vs_3_0 (texldl)
  kConstBool = 14,     // b#, vs_2_0 on
  kLoop = 15,          // aL, vs_2_0 on
  kLabel = 18,         // l#, vs_2_0 on (call, callnz, label)
  kPredicate = 19,     // p0, vs_2_x on
};

// How many registers of a file each model has (0: the file does not exist in that model), in
// ShaderModel order. Constants: the minimum bank a device offers (a run may have more, up to what the
// register number can hold).
struct RegisterFileLimits {
  RegisterFile file;
  std::array<int, kShaderModelCount> count;
};
inline constexpr std::array kRegisterFileLimits = {
    //                                           vs_1_1 vs_2_0 vs_2_x vs_3_0
    RegisterFileLimits{RegisterFile::kTemp, {12, 12, 32, 32}},
    RegisterFileLimits{RegisterFile::kInput, {16, 16, 16, 16}},
    RegisterFileLimits{RegisterFile::kConst, {96, 256, 256, 256}},
    RegisterFileLimits{RegisterFile::kAddress, {1, 1, 1, 1}},
    RegisterFileLimits{RegisterFile::kRasterOut, {3, 3, 3, 0}},
    RegisterFileLimits{RegisterFile::kAttributeOut, {2, 2, 2, 0}},
    RegisterFileLimits{RegisterFile::kTexCoordOut, {8, 8, 8, 12}},
    RegisterFileLimits{RegisterFile::kConstInt, {0, 16, 16, 16}},
    RegisterFileLimits{RegisterFile::kConstBool, {0, 16, 16, 16}},
    RegisterFileLimits{RegisterFile::kLoop, {0, 1, 1, 1}},
    RegisterFileLimits{RegisterFile::kPredicate, {0, 0, 1, 1}},
    RegisterFileLimits{RegisterFile::kSampler, {0, 0, 0, 4}},
    RegisterFileLimits{RegisterFile::kLabel, {0, 2048, 2048, 2048}},
};

// Registers of `file` in `model` (0 for a file or a register type number it does not have).
constexpr int RegisterCount(RegisterFile file, ShaderModel model) {
  for (const RegisterFileLimits& limits : kRegisterFileLimits) {
    if (limits.file == file) return limits.count[static_cast<int>(model)];
  }
  return 0;
}

// The register file of D3D register type `type` when `model` has it.
constexpr std::optional<RegisterFile> RegisterFileOfType(std::uint32_t type, ShaderModel model) {
  for (const RegisterFileLimits& limits : kRegisterFileLimits) {
    if (static_cast<std::uint32_t>(limits.file) == type && limits.count[static_cast<int>(model)] > 0) return limits.file;
  }
  return std::nullopt;
}

// A later model has every register an earlier one has.
static_assert([] {
  for (const RegisterFileLimits& limits : kRegisterFileLimits) {
    for (int m = 1; m < kShaderModelCount; ++m) {
      const bool output = limits.file == RegisterFile::kRasterOut || limits.file == RegisterFile::kAttributeOut;
      if (!output && limits.count[m] < limits.count[m - 1]) return false;  // vs_3_0 renames the outputs
    }
  }
  return true;
}());

}  // namespace vs11
