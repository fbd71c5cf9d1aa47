// Value types for a decoded vs_1_1 program: registers, swizzles, masks, operands, instructions.
// The token layout lives in vm/asm/bytecode.cc only; these types carry meaning, not bits.
#pragma once

#include <array>
#include <bit>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "vm/core/diagnostic.h"
#include "vm/core/isa.h"

namespace vs11 {

// RegisterFile, the register types, is in vm/core/shader_model.h with each model's register counts.
inline constexpr int kRasterOutPosition = 0;
inline constexpr int kRasterOutFog = 1;
inline constexpr int kRasterOutPointSize = 2;

constexpr bool IsOutput(RegisterFile file) {
  return file == RegisterFile::kRasterOut || file == RegisterFile::kAttributeOut ||
         file == RegisterFile::kTexCoordOut;
}

// The register that indexes a relative operand: a0 with a swizzle choosing its lane (vs_1_1 has only
// a0.x), or aL (later models; its swizzle is always .xyzw).
struct AddressRegister {
  RegisterFile file = RegisterFile::kAddress;
  std::uint8_t swizzle_bits = 0x00;  // Swizzle bits: .x
  friend constexpr bool operator==(const AddressRegister&, const AddressRegister&) = default;
};

struct RegisterRef {
  RegisterFile file = RegisterFile::kTemp;
  int index = 0;          // for a relative constant: the offset n of c[a0.x + n]
  bool relative = false;  // c[a0.x + index]
  AddressRegister address{};  // what indexes a relative register
  friend constexpr bool operator==(const RegisterRef&, const RegisterRef&) = default;
};

// oFog and oPts hold one value: the rasterizer reads lane x only (§7). Any write mask is encodable.
constexpr bool IsScalarOutput(const RegisterRef& reg) {
  return reg.file == RegisterFile::kRasterOut && (reg.index == kRasterOutFog || reg.index == kRasterOutPointSize);
}

// Lane selectors packed as D3D does: two bits per lane, lane x in the low bits (§4.5).
class Swizzle {
 public:
  static constexpr std::uint8_t kIdentityBits = 0xE4;  // .xyzw
  constexpr Swizzle() = default;
  constexpr explicit Swizzle(std::uint8_t bits) : bits_(bits) {}
  static constexpr Swizzle Replicate(int lane) { return Swizzle(static_cast<std::uint8_t>(lane * 0x55)); }
  constexpr int operator[](int lane) const { return (bits_ >> (2 * lane)) & 3; }
  constexpr std::uint8_t bits() const { return bits_; }
  constexpr bool is_identity() const { return bits_ == kIdentityBits; }
  constexpr bool is_replicate() const { return (*this)[0] == (*this)[1] && (*this)[1] == (*this)[2] && (*this)[2] == (*this)[3]; }
  friend constexpr bool operator==(Swizzle, Swizzle) = default;

 private:
  std::uint8_t bits_ = kIdentityBits;
};

// Destination lanes, bit i = lane i (x = 1, y = 2, z = 4, w = 8).
class WriteMask {
 public:
  static constexpr std::uint8_t kAllLanes = kLanesXyzw;
  constexpr WriteMask() = default;
  constexpr explicit WriteMask(std::uint8_t bits) : bits_(bits) {}
  constexpr bool has(int lane) const { return (bits_ >> lane) & 1; }
  constexpr std::uint8_t bits() const { return bits_; }
  constexpr bool is_full() const { return bits_ == kAllLanes; }
  constexpr int count() const { return std::popcount(bits_); }
  friend constexpr bool operator==(WriteMask, WriteMask) = default;

 private:
  std::uint8_t bits_ = kAllLanes;
};

struct SourceOperand {
  RegisterRef reg;
  Swizzle swizzle;
  bool negate = false;
  bool absolute = false;     // r0_abs (vs_3_0); with negate: -r0_abs
  bool logical_not = false;  // !b0, !p0 (flow-control conditions and predicates)
  friend constexpr bool operator==(const SourceOperand&, const SourceOperand&) = default;
};

struct DestOperand {
  RegisterRef reg;
  WriteMask mask;
  bool saturate = false;  // _sat (vs_2_0 on): the result clamped to [0, 1]
  friend constexpr bool operator==(const DestOperand&, const DestOperand&) = default;
};

// IEEE-754 single-precision bits of the def literals that are words, not numbers: the sign of `-nan`
// and `-inf`, +infinity, and the quiet NaN the assembler writes for `nan` (the disassembler prints
// only this NaN as plain `nan`; any other payload gets a comment).
inline constexpr std::uint32_t kFloatSignBit = 0x80000000u;
inline constexpr std::uint32_t kInfinityBits = 0x7F800000u;
inline constexpr std::uint32_t kQuietNanBits = 0x7FC00000u;

struct Instruction {
  Opcode opcode = Opcode::kNop;
  DestOperand dest;                       // unused by nop
  std::array<SourceOperand, 3> sources;   // the first Info(opcode).source_count() are used
  int usage = 0;                          // dcl: D3DDECLUSAGE value
  int usage_index = 0;                    // dcl: 0-15
  std::array<std::uint32_t, 4> def_bits{};  // def: the four floats as raw IEEE bits (kept exact);
                                            // defi: the four integers; defb: the bool in def_bits[0]
  int comparison = 0;          // if_comp, break_comp, setp_comp: 1 gt ... 6 le (kComparisonNames)
  int sampler_type = 0;        // dcl on s#: 2 2d, 3 cube, 4 volume (kSamplerTypeNames)
  bool predicated = false;     // (p0) / (!p0) before the instruction (vs_2_x on)
  SourceOperand predicate{RegisterRef{RegisterFile::kPredicate, 0, false, {}}, Swizzle(), false, false, false};

  const OpcodeInfo& info() const { return Info(opcode); }
  std::array<float, 4> def_values() const {
    return {std::bit_cast<float>(def_bits[0]), std::bit_cast<float>(def_bits[1]),
            std::bit_cast<float>(def_bits[2]), std::bit_cast<float>(def_bits[3])};
  }
  friend bool operator==(const Instruction&, const Instruction&) = default;
};

// Comment tokens are kept so that disassembly and re-assembly lose nothing.
struct CommentBlock {
  int before_instruction = 0;  // index into Program::instructions it precedes
  std::vector<std::uint32_t> words;
  friend bool operator==(const CommentBlock&, const CommentBlock&) = default;
};

// Structured control flow, for the shader models after vs_1_1 (loop/endloop, rep/endrep, if/else/endif,
// call and label, predicated blocks): the instruction list stays flat, as the token stream is, and
// each construct is a region over a span of it, listed parent first, so that the regions of vm/ir's
// graph (vm/ir/graph.h) map one to one. A new construct is a new kind and the instructions that open
// and close it, not a new program model. vs_1_1 has none: the whole list is the body.
enum class ControlKind : std::uint8_t { kBody };  // later: loop, rep, if, else, subroutine, predicated
struct ControlRegion {
  ControlKind kind = ControlKind::kBody;
  int first = 0;    // the instruction that opens it (index into Program::instructions)
  int end = 0;      // one past the instruction that closes it
  int parent = -1;  // index into Program::regions; -1 for the body
  int label = -1;   // a subroutine's label number; -1 for other kinds
  friend bool operator==(const ControlRegion&, const ControlRegion&) = default;
};

struct Program {
  std::uint32_t version = kVersionVs11;
  std::vector<Instruction> instructions;  // dcl and def included, in stream order
  std::vector<ControlRegion> regions;     // empty: straight-line code (vs_1_1)
  std::vector<CommentBlock> comments;
  // Where each instruction came from, when assembled from text (same length as instructions), or empty.
  std::vector<SourceLoc> source_locs;
  // The word offset of each instruction token, when decoded from bytecode (same length as
  // instructions), or empty.
  std::vector<long> word_offsets;

  // The model the version token names; vs_1_1's for a token of none (the validator reports it).
  ShaderModel model() const { return ShaderModelOfVersion(version).value_or(ShaderModel::kVs11); }
  SourceLoc LocOf(int instruction_index) const {
    return instruction_index >= 0 && instruction_index < static_cast<int>(source_locs.size())
               ? source_locs[instruction_index]
               : SourceLoc{};
  }
  // -1 when unknown (Diagnostic::word_offset's convention).
  long WordOffsetOf(int instruction_index) const {
    return instruction_index >= 0 && instruction_index < static_cast<int>(word_offsets.size())
               ? word_offsets[instruction_index]
               : -1;
  }
};

// Lane letters.
inline constexpr std::array<char, 4> kLaneLetters = {'x', 'y', 'z', 'w'};

// Static figures of a program used by `vs11 count` and programs/README.md.
struct ProgramStats {
  int instructions = 0;  // executable instructions (dcl/def excluded)
  int slots = 0;         // §2.7 cost: macros and multi-slot instructions by the table
  int constants = 0;     // distinct constant registers read (a relative operand counts its rows once each, by offset)
  int temporaries = 0;   // distinct r# written or read
  int inputs = 0;        // distinct v# read
  bool uses_relative_addressing = false;
};
ProgramStats ComputeStats(const Program& program);

}  // namespace vs11
