// The vertex-shader instruction set of every model, defined once. Every other part of the machine
// (assembler, disassembler, validator, engines, instruction counts) reads these rows instead of keeping
// its own list. Sources: ../shared/spec/vs_1_1.md §3.2 (vs_1_1 opcodes, operand forms, slots, mask
// rules); the later models' opcode numbers and operand layouts from Microsoft's assembler output as
// Wine's tests record it (spec sections "vs_2_0", "vs_2_x", "vs_3_0"), their slot costs from the D3D9
// reference's per-instruction pages.
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
  // Later models:
  kSource1,          // rep i#, if b#, label l#, call l#, breakp p0.c: one source, no destination
  kSource2,          // loop aL, i#; callnz l#, b#; if_gt s0, s1; break_gt s0, s1
  kSinCos,           // sincos d, s, c1, c2 (vs_2_0, vs_2_x) or sincos d, s (vs_3_0): SourceCount()
  kIntDefinition,    // defi i#, n, n, n, n: a dest token, then four 32-bit integers
  kBoolDefinition,   // defb b#, true|false: a dest token, then one word (1 or 0)
};

// What the arithmetic does with its sources; selects the shared kernel form (vm/core/semantics.h).
enum class ResultKind : std::uint8_t {
  kNoResult,       // nop, dcl, def; the later models' flow control and texldl (no arithmetic kernel)
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
  X(Def, "def", 0x51, kDefinition, kNoResult, 0, kFull, kLanesXyzw, 0, 0, kVs11)     \
  X(Lrp, "lrp", 0x12, kDest3, kComponentwise, 2, kAny, kLanesXyzw, 0, 0, kVs20)       \
  X(Call, "call", 0x19, kSource1, kNoResult, 2, kAny, kLanesXyzw, 0, 0, kVs20)     \
  X(Callnz, "callnz", 0x1A, kSource2, kNoResult, 3, kAny, kLanesXyzw, 0, 0, kVs20) \
  X(Loop, "loop", 0x1B, kSource2, kNoResult, 3, kAny, kLanesXyzw, 0, 0, kVs20)     \
  X(Ret, "ret", 0x1C, kNone, kNoResult, 1, kAny, kLanesXyzw, 0, 0, kVs20)          \
  X(Endloop, "endloop", 0x1D, kNone, kNoResult, 2, kAny, kLanesXyzw, 0, 0, kVs20)  \
  X(Label, "label", 0x1E, kSource1, kNoResult, 0, kAny, kLanesXyzw, 0, 0, kVs20)   \
  X(Pow, "pow", 0x20, kDest2, kVector, 3, kAny, kLanesXyzw, 0, 0, kVs20)              \
  X(Crs, "crs", 0x21, kDest2, kVector, 2, kAny, kLanesXyzw, 0, 0, kVs20)              \
  X(Sgn, "sgn", 0x22, kDest3, kComponentwise, 3, kAny, kLanesXyzw, 0, 0, kVs20)       \
  X(Abs, "abs", 0x23, kDest1, kComponentwise, 1, kAny, kLanesXyzw, 0, 0, kVs20)       \
  X(Nrm, "nrm", 0x24, kDest1, kVector, 3, kAny, kLanesXyzw, 0, 0, kVs20)              \
  X(Sincos, "sincos", 0x25, kSinCos, kVector, 8, kAny, kLanesXyzw, 0, 0, kVs20)       \
  X(Rep, "rep", 0x26, kSource1, kNoResult, 3, kAny, kLanesXyzw, 0, 0, kVs20)       \
  X(Endrep, "endrep", 0x27, kNone, kNoResult, 2, kAny, kLanesXyzw, 0, 0, kVs20)    \
  X(If, "if", 0x28, kSource1, kNoResult, 3, kAny, kLanesXyzw, 0, 0, kVs20)         \
  X(Else, "else", 0x2A, kNone, kNoResult, 1, kAny, kLanesXyzw, 0, 0, kVs20)        \
  X(Endif, "endif", 0x2B, kNone, kNoResult, 1, kAny, kLanesXyzw, 0, 0, kVs20)      \
  X(Mova, "mova", 0x2E, kDest1, kComponentwise, 1, kAny, kLanesXyzw, 0, 0, kVs20)     \
  X(Defb, "defb", 0x2F, kBoolDefinition, kNoResult, 0, kFull, kLanesXyzw, 0, 0, kVs20) \
  X(Defi, "defi", 0x30, kIntDefinition, kNoResult, 0, kFull, kLanesXyzw, 0, 0, kVs20) \
  X(Ifc, "ifc", 0x29, kSource2, kNoResult, 3, kAny, kLanesXyzw, 0, 0, kVs2x)       \
  X(Break, "break", 0x2C, kNone, kNoResult, 1, kAny, kLanesXyzw, 0, 0, kVs2x)      \
  X(Breakc, "breakc", 0x2D, kSource2, kNoResult, 3, kAny, kLanesXyzw, 0, 0, kVs2x) \
  X(Setp, "setp", 0x5E, kDest2, kComponentwise, 1, kAny, kLanesXyzw, 0, 0, kVs2x)     \
  X(Breakp, "breakp", 0x60, kSource1, kNoResult, 3, kAny, kLanesXyzw, 0, 0, kVs2x) \
  X(Texldl, "texldl", 0x5F, kDest2, kNoResult, 2, kAny, kLanesXyzw, 0, 0, kVs30)

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

  // Number of source operands (0 to 3); sincos's vs_2_0 form (SourceCount gives each model's).
  constexpr int source_count() const {
    switch (shape) {
      case OperandShape::kDest1: return 1;
      case OperandShape::kDest2: return 2;
      case OperandShape::kDest3: return 3;
      case OperandShape::kSource1: return 1;
      case OperandShape::kSource2: return 2;
      case OperandShape::kSinCos: return 3;
      default: return 0;
    }
  }
  constexpr bool has_dest() const {
    return shape != OperandShape::kNone && shape != OperandShape::kSource1 && shape != OperandShape::kSource2;
  }
  constexpr bool is_definition() const {
    return shape == OperandShape::kDefinition || shape == OperandShape::kIntDefinition ||
           shape == OperandShape::kBoolDefinition;
  }
  // Consecutive registers that source `source` reads: matrix_rows for the matrix of m*x*, else 1.
  constexpr int registers_read(int source) const {
    return kind == ResultKind::kMatrix && source == kMatrixSource ? matrix_rows : 1;
  }
  // Destination lanes the result can reach before the write mask: a matrix fills one lane per row.
  constexpr int result_lanes() const { return kind == ResultKind::kMatrix ? matrix_rows : 4; }
  // Parameter tokens after the instruction token, without the extra tokens of relative addressing and
  // predication in later models (vs_1_1 has no length field: §4.3).
  constexpr int parameter_tokens() const {
    switch (shape) {
      case OperandShape::kNone: return 0;
      case OperandShape::kDeclaration: return 2;
      case OperandShape::kDefinition: return 5;
      case OperandShape::kIntDefinition: return 5;
      case OperandShape::kBoolDefinition: return 2;
      default: return (has_dest() ? 1 : 0) + source_count();
    }
  }
  // Only mov writes the address register (mov a0.x, src: §1.4, §3.2).
  constexpr bool can_write_address() const { return opcode == Opcode::kMov; }
  // dcl and def configure the shader; everything else executes.
  constexpr bool is_executable() const { return shape != OperandShape::kDeclaration && !is_definition(); }
};

inline constexpr std::array kOpcodeTable = {
#define VS11_OPCODE_ROW(name, mnemonic, token, shape, kind, slots, mask, default_mask, dot, rows, since) \
  OpcodeInfo{Opcode::k##name, mnemonic, token, OperandShape::shape, ResultKind::kind, slots,               \
             MaskRule::mask, default_mask, dot, rows, ShaderModel::since},
    VS11_OPCODES(VS11_OPCODE_ROW)
#undef VS11_OPCODE_ROW
};
inline constexpr int kOpcodeCount = static_cast<int>(kOpcodeTable.size());

// The spec lists 28 vs_1_1 opcodes including dcl and def (§3.2); the enum follows the table order. The
// rows go model by model, each model's by token, so that vs_1_1's opcodes keep their numbers.
inline constexpr int kVs11OpcodeCount = 28;
static_assert([] {
  int vs11_rows = 0;
  for (int i = 0; i < kOpcodeCount; ++i) {
    const OpcodeInfo& row = kOpcodeTable[i];
    if (static_cast<int>(row.opcode) != i) return false;
    vs11_rows += row.since == ShaderModel::kVs11 ? 1 : 0;
    if (i == 0) continue;
    const OpcodeInfo& previous = kOpcodeTable[i - 1];
    if (row.since < previous.since) return false;
    if (row.since == previous.since && row.since == ShaderModel::kVs11 && row.token <= previous.token) return false;
    for (int j = 0; j < i; ++j) {
      if (kOpcodeTable[j].token == row.token) return false;
    }
  }
  return vs11_rows == kVs11OpcodeCount;
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
// Source operands in `model`: sincos lost its two constant operands in vs_3_0.
constexpr int SourceCount(const OpcodeInfo& info, ShaderModel model) {
  return info.shape == OperandShape::kSinCos && model >= ShaderModel::kVs30 ? 1 : info.source_count();
}

// if_gt, break_ne, setp_le: the comparison in bits 16-18 of the instruction token (D3DSHADER_COMPARISON).
constexpr bool TakesComparison(Opcode opcode) {
  return opcode == Opcode::kIfc || opcode == Opcode::kBreakc || opcode == Opcode::kSetp;
}
// The mnemonic a comparison suffix follows: "if" for ifc, "break" for breakc, "setp" for setp.
constexpr std::string_view ComparisonStem(Opcode opcode) {
  return opcode == Opcode::kIfc ? "if" : opcode == Opcode::kBreakc ? "break" : "setp";
}
// Index = the comparison's value (1-6); 0 and 7 are not comparisons.
inline constexpr std::array<std::string_view, 7> kComparisonNames = {"", "gt", "eq", "ge", "lt", "ne", "le"};
std::optional<int> ComparisonFromName(std::string_view name);  // case-insensitive

// D3DSAMPLER_TEXTURE_TYPE (bits 27-30 of a sampler dcl's usage token): dcl_2d, dcl_cube, dcl_volume.
inline constexpr std::array<std::string_view, 5> kSamplerTypeNames = {"", "", "2d", "cube", "volume"};
inline constexpr int kSampler2d = 2;
std::optional<int> SamplerTypeFromName(std::string_view name);  // case-insensitive
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
