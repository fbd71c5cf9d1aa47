// Bytecode -> .vsh text (spec §4.13). The text is what the assembler (vm/asm/assembler.h) reads back:
// for every program the assembler can produce, AssembleSource(Disassemble(p)) encodes to exactly
// Encode(p), except that comment blocks, printed as `;` lines, are dropped.
//
// A program of a later model (vs_2_0, vs_2_x, vs_3_0) always prints as DX9 text: relative operands as
// c3[a0.x], c3[a0] (a0's swizzle .xyzw), c3[aL], o12[a0.x]; defi values as integers, defb as true/false.
// A program of vs_1_1 with a dcl prints as DX9 text: first line vs_1_1 (vs_1_0 for version 1.0), relative
// constants as c<n>[a0.x]. A program without one comes from DX8 source and prints as DX8 text, which
// needs no dcl to validate again: first line vs.1.1 (vs.1.0), relative constants as c[a0.x + n].
// Both: one instruction per line; lower-case mnemonics; operands separated by ", "; write mask
// omitted when it is .xyzw and the opcode's default (so m3x3 prints .xyz, m3x3 .xyzw keeps its mask,
// oFog.x keeps its mask); swizzle omitted when identity, one letter when replicated, else four
// letters; dcl_<usage><index> with index 0 omitted; def values in the shortest text that reads back to
// the same float ("1", "0.5", "1e-40"); infinities as inf / -inf and NaN as nan / -nan.
// A NaN whose payload is not the canonical quiet NaN 0x7FC00000 cannot be written as text: it is
// printed as nan (reassembling to 0x7FC00000) followed by a `;` comment giving the original bits.
#pragma once

#include <string>

#include "vm/core/program.h"

namespace vs11 {

enum class Syntax { kDx9, kDx8 };

// kDx9 when the program has a dcl, kDx8 otherwise.
Syntax SyntaxOf(const Program& program);

// The whole program in SyntaxOf(program), one line per instruction, each line ending in '\n'.
std::string Disassemble(const Program& program);

// One instruction without a trailing newline, e.g. "dp4 r1.x, v1, c3[a0.x]" (for messages and tools), as
// a program of `model` spells it (later models: "(!p0) add_sat r2, r2_abs, c0[aL]", "if_gt r0, r1").
std::string FormatInstruction(const Instruction& instruction, Syntax syntax = Syntax::kDx9,
                              ShaderModel model = ShaderModel::kVs11);

// Single operands as they appear in DX9 text: "r1.x" (any mask that is not full), "-c3[a0.x].y".
std::string FormatDest(const DestOperand& dest, ShaderModel model = ShaderModel::kVs11);
std::string FormatSource(const SourceOperand& source, Syntax syntax = Syntax::kDx9,
                         ShaderModel model = ShaderModel::kVs11);

}  // namespace vs11
