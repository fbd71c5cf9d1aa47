// The vs_1_1 instruction set, defined once. Every other part of the machine (assembler, disassembler,
// validator, engines, instruction counts) reads these rows instead of keeping its own list.
// Source: ../shared/spec/vs_1_1.md §3.2 (opcodes, operand forms, slots, mask rules).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>

#include "vm/core/shader_model.h"

namespace vs11 {

// How an instruction's operands are laid out in source and in the token stream.
enum class OperandShape : std::uint8_t {
  kNone,         // nop
  kDest1,        // d, s
  kDest2,        // d, s0, s1
  kDest3,        // d, s0, s1, s2
  kDeclaration,  // dcl_usage[n] v#: a usage token, then a dest token
  kDefinition,   // def c#, f, f, f, f: a dest token, then four raw floats
};

// What the arithmetic does with its sources; selects the shared kernel form (vm/core/semantics.h).
enum class ResultKind : std::uint8_t {
  kNoResult,       // nop, dcl, def
  kComponentwise,  // r[i] = f(a[i], b[i], c[i]) for each written lane
  kDotProduct,     // one value from lanes 0..dot_width-1, replicated
  kScalar,         // one value from the source's w lane (§3.1), replicated
  kVector,         // a whole vec4 from whole vec4 sources (lit, dst, expp, logp)
  kMatrix,         // row i = dot(s0, register s1 + i) over dot_width lanes, for matrix_rows rows
};

// Which destination write masks vs_1_1 accepts (§3.2 "dest mask rule").
enum class MaskRule : std::uint8_t {
  kAny,
  kYOrXy,   // frc
  kXy,      // m3x2
  kXyz,     // m3x3, m4x3
  kXyzw,    // m3x4, m4x4
  kFull,    // dcl, def: always emitted as .xyzw
};

// Write-mask bits (x = bit 0 ... w = bit 3, as in the dest token §4.5) of the masks the table names.
inline constexpr std::uint8_t kLanesXy = 0x3;
inline constexpr std::uint8_t kLanesXyz = 0x7;
inline constexpr std::uint8_t kLanesXyzw = 0xF;

// name, mnemonic, opcode token, operand shape, result kind, slots, mask rule, default mask, dot width,
// matrix rows, first shader model (vm/core/shader_model.h: the model that introduced the opcode; every
// later one keeps it). The default mask is what the assembler writes when the destination has none:
// the lanes a matrix macro writes (m3x3 r0, v0, c0 is emitted as .xyz, as Microsoft's assembler does and
// MojoShader's opcode table records), .xyzw for everything else (frc included: it is then invalid).
#define VS11_OPCODES(X)                                                                 \
  X(Nop, "nop", 0x00, kNone, kNoResult, 1, kAny, kLanesXyzw, 0, 0, kVs11)               \
  X(Mov, "mov", 0x01, kDest1, kComponentwise, 1, kAny, kLanesXyzw, 0, 0, kVs11)         \
  X(Add, "add", 0x02, kDest2, kComponentwise, 1, kAny, kLanesXyzw, 0, 0, kVs11)         \
  X(Sub, "sub", 0x03, kDest2, kComponentwise, 1, kAny, kLanesXyzw, 0, 0, kVs11)         \
  X(Mad, "mad", 0x04, kDest3, kComponentwise, 1, kAny, kLanesXyzw, 0, 0, kVs11)         \
  X(Mul, "mul", 0x05, kDest2, kComponentwise, 1, kAny, kLanesXyzw, 0, 0, kVs11)         \
  X(Rcp, "rcp", 0x06, kDest1, kScalar, 1, kAny, kLanesXyzw, 0, 0, kVs11)                \
  X(Rsq, "rsq", 0x07, kDest1, kScalar, 1, kAny, kLanesXyzw, 0, 0, kVs11)                \
  X(Dp3, "dp3", 0x08, kDest2, kDotProduct, 1, kAny, kLanesXyzw, 3, 0, kVs11)            \
  X(Dp4, "dp4", 0x09, kDest2, kDotProduct, 1, kAny, kLanesXyzw, 4, 0, kVs11)            \
  X(Min, "min", 0x0A, kDest2, kComponentwise, 1, kAny, kLanesXyzw, 0, 0, kVs11)         \
  X(Max, "max", 0x0B, kDest2, kComponentwise, 1, kAny, kLanesXyzw, 0, 0, kVs11)         \
  X(Slt, "slt", 0x0C, kDest2, kComponentwise, 1, kAny, kLanesXyzw, 0, 0, kVs11)         \
  X(Sge, "sge", 0x0D, kDest2, kComponentwise, 1, kAny, kLanesXyzw, 0, 0, kVs11)         \
  X(Exp, "exp", 0x0E, kDest1, kScalar, 10, kAny, kLanesXyzw, 0, 0, kVs11)               \
  X(Log, "log", 0x0F, kDest1, kScalar, 10, kAny, kLanesXyzw, 0, 0, kVs11)               \
  X(Lit, "lit", 0x10, kDest1, kVector, 1, kAny, kLanesXyzw, 0, 0, kVs11)                \
  X(Dst, "dst", 0x11, kDest2, kVector, 1, kAny, kLanesXyzw, 0, 0, kVs11)                \
  X(Frc, "frc", 0x13, kDest1, kComponentwise, 3, kYOrXy, kLanesXyzw, 0, 0, kVs11)       \
  X(M4x4, "m4x4", 0x14, kDest2, kMatrix, 4, kXyzw, kLanesXyzw, 4, 4, kVs11)             \
  X(M4x3, "m4x3", 0x15, kDest2, kMatrix, 3, kXyz, kLanesXyz, 4, 3, kVs11)               \
  X(M3x4, "m3x4", 0x16, kDest2, kMatrix, 4, kXyzw, kLanesXyzw, 3, 4, kVs11)             \
  X(M3x3, "m3x3", 0x17, kDest2, kMatrix, 3, kXyz, kLanesXyz, 3, 3, kVs11)               \
  X(M3x2, "m3x2", 0x18, kDest2, kMatrix, 2, kXy, kLanesXy, 3, 2, kVs11)                 \
  X(Dcl, "dcl", 0x1F, kDeclaration, kNoResult, 0, kFull, kLanesXyzw, 0, 0, kVs11)       \
  X(Expp, "expp", 0x4E, kDest1, kVector, 1, kAny, kLanesXyzw, 0, 0, kVs11)              \
  X(Logp, "logp", 0x4F, kDest1, kVector, 1, kAny, kLanesXyzw, 0, 0, kVs11)              \
  X(Def, "def", 0x51, kDefinition, kNoResult, 0, kFull, kLanesXyzw, 0, 0, kVs11)

enum class Opcode : std::uint8_t {
#define VS11_OPCODE_ENUM(name, ...) k##name,
  VS11_OPCODES(VS11_OPCODE_ENUM)
#undef VS11_OPCODE_ENUM
};

struct OpcodeInfo {
  Opcode opcode;
  std::string_view mnemonic;
  std::uint16_t token;  // bits 0-15 of the instruction token
  OperandShape shape;
  ResultKind kind;
  int slots;            // cost against the 128-slot limit (§2.7)
  MaskRule mask_rule;
  std::uint8_t default_mask;  // WriteMask bits written when the source gives no mask
  int dot_width;        // lanes summed by dp3/dp4 and each matrix row
  int matrix_rows;      // rows (and registers of s1) read by m*x*
  ShaderModel since;    // the first model that has it

  // The source of m*x* that names the matrix's first row (m4x4 r0, v0, c4: c4..c7).
  static constexpr int kMatrixSource = 1;

  // Number of source operands (0 to 3).
  constexpr int source_count() const {
    switch (shape) {
      case OperandShape::kDest1: return 1;
      case OperandShape::kDest2: return 2;
      case OperandShape::kDest3: return 3;
      default: return 0;
    }
  }
  constexpr bool has_dest() const { return shape != OperandShape::kNone; }
  // Consecutive registers that source `source` reads: matrix_rows for the matrix of m*x*, else 1.
  constexpr int registers_read(int source) const {
    return kind == ResultKind::kMatrix && source == kMatrixSource ? matrix_rows : 1;
  }
  // Destination lanes the result can reach before the write mask: a matrix fills one lane per row.
  constexpr int result_lanes() const { return kind == ResultKind::kMatrix ? matrix_rows : 4; }
  // Parameter tokens after the instruction token (vs_1_1 has no length field: §4.3).
  constexpr int parameter_tokens() const {
    switch (shape) {
      case OperandShape::kNone: return 0;
      case OperandShape::kDeclaration: return 2;
      case OperandShape::kDefinition: return 5;
      default: return 1 + source_count();
    }
  }
  // Only mov writes the address register (mov a0.x, src: §1.4, §3.2).
  constexpr bool can_write_address() const { return opcode == Opcode::kMov; }
  // dcl and def configure the shader; everything else executes.
  constexpr bool is_executable() const {
    return shape != OperandShape::kDeclaration && shape != OperandShape::kDefinition;
  }
};

inline constexpr std::array kOpcodeTable = {
#define VS11_OPCODE_ROW(name, mnemonic, token, shape, kind, slots, mask, default_mask, dot, rows, since) \
  OpcodeInfo{Opcode::k##name, mnemonic, token, OperandShape::shape, ResultKind::kind, slots,               \
             MaskRule::mask, default_mask, dot, rows, ShaderModel::since},
    VS11_OPCODES(VS11_OPCODE_ROW)
#undef VS11_OPCODE_ROW
};
inline constexpr int kOpcodeCount = static_cast<int>(kOpcodeTable.size());

// The spec lists 28 vs_1_1 opcodes including dcl and def (§3.2); the enum follows the table order.
static_assert(kOpcodeCount == 28);
static_assert([] {
  for (int i = 0; i < kOpcodeCount; ++i) {
    if (static_cast<int>(kOpcodeTable[i].opcode) != i) return false;
    if (i > 0 && kOpcodeTable[i].token <= kOpcodeTable[i - 1].token) return false;
  }
  return true;
}());

// Where the rule allows a single mask, the assembler's default is that mask.
static_assert([] {
  for (const OpcodeInfo& info : kOpcodeTable) {
    const int only = info.mask_rule == MaskRule::kXy     ? kLanesXy
                     : info.mask_rule == MaskRule::kXyz  ? kLanesXyz
                     : info.mask_rule == MaskRule::kXyzw ? kLanesXyzw
                     : info.mask_rule == MaskRule::kFull ? kLanesXyzw
                                                         : info.default_mask;
    if (info.default_mask != only) return false;
  }
  return true;
}());

constexpr const OpcodeInfo& Info(Opcode opcode) { return kOpcodeTable[static_cast<int>(opcode)]; }
// Whether programs of `model` may use the opcode.
constexpr bool OpcodeAllowed(const OpcodeInfo& info, ShaderModel model) { return model >= info.since; }
std::optional<Opcode> OpcodeFromToken(std::uint16_t token);
std::optional<Opcode> OpcodeFromMnemonic(std::string_view mnemonic);  // case-insensitive

// D3DDECLUSAGE (§4.9): the value is the index; the dcl_ spelling is the lower-case name.
inline constexpr std::array<std::string_view, 14> kDeclUsageNames = {
    "position", "blendweight", "blendindices", "normal",    "psize", "texcoord", "tangent",
    "binormal", "tessfactor",  "positiont",    "color",     "fog",   "depth",    "sample"};
inline constexpr int kDeclUsageNormal = 3;
inline constexpr int kMaxDeclUsageIndex = 15;
std::optional<int> DeclUsageFromName(std::string_view name);  // case-insensitive

// Machine limits (§1.1, §2.7).
inline constexpr int kMaxInstructionSlots = 128;
inline constexpr int kTempRegisterCount = RegisterCount(RegisterFile::kTemp, ShaderModel::kVs11);
inline constexpr int kInputRegisterCount = RegisterCount(RegisterFile::kInput, ShaderModel::kVs11);
// D3DCAPS9.MaxVertexShaderConst minimum for vs_1_1.
inline constexpr int kDefaultConstantCount = RegisterCount(RegisterFile::kConst, ShaderModel::kVs11);
inline constexpr int kMaxConstantIndex = 2047;    // what the 11-bit register number can hold
inline constexpr int kTexCoordOutputCount = RegisterCount(RegisterFile::kTexCoordOut, ShaderModel::kVs11);
inline constexpr int kColorOutputCount = RegisterCount(RegisterFile::kAttributeOut, ShaderModel::kVs11);

// Version tokens (§4.2).
inline constexpr std::uint32_t kVersionVs11 = Info(ShaderModel::kVs11).version_token;
inline constexpr std::uint32_t kVersionVs10 = 0xFFFE0100;

}  // namespace vs11
