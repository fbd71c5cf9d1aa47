// The .vsh text assembler (spec §2): preprocesses the text, parses one statement per line with a
// small lexer (vm/asm/lexer.h) and a table-driven grammar, and builds a Program whose Encode() is the
// token stream Microsoft's assembler writes (§4, §5). Then, unless switched off, it runs the
// validator (vm/asm/validator.h), which checks the rules of §6 that are not syntax.
//
// Accepted syntax, in brief:
//   version      vs_1_1 | vs.1.1 | vs.1.0 | vs_1_0   (first statement; case-insensitive)
//   instruction  mnemonic [dest [, src ...]]       (one per line; mnemonics, register names and
//                                                   component letters are case-insensitive)
//   dcl          dcl_<usage>[index] v#               (usage from §4.9, index 0-15, default 0)
//   def          def c#, f, f, f, f                  (1  1.  .5  -1.5f  1e-3  nan  inf  -inf)
//   dest         [register][.mask]                   (mask: 1-4 of xyzw/rgba, increasing order;
//                                                   none: the opcode's default mask, see below)
//   src          [-]register[.swizzle]               (1-4 letters, last one repeated)
//   register     r# v# c# a0 oPos oFog oPts oD# oT#  c[n] c[a + b] c<n>[a0.x] c[a0.x + n] c[n + a0.x]
// Register numbers must fit the 11-bit token field (0-2047); whether a register exists (r12, c96,
// v16) is the validator's question. Only constants may be indexed; the offset of a relative constant
// is the sum of every integer in the brackets plus the base number, and must not be negative.
// A destination without a mask gets the opcode's default mask: .xyz for m3x3 and m4x3, .xy for m3x2,
// .xyzw otherwise. A written mask is emitted as written, oFog and oPts included (`mov oFog.x, r0.x`
// keeps mask .x; whether a mask is allowed is the validator's question).
//
// Later models (vs_2_0 | vs.2.0, vs_2_x | vs.2.x, vs_3_0 | vs.3.0; the tokens are Microsoft's, spec
// sections "vs_2_0" to "vs_3_0"): the opcode table's later rows; flow-control operands (rep i0, loop aL,
// i0, if [!]b0, call l0, callnz l0, !p0.z); if_gt/break_ne/setp_le comparisons; (p0) / (!p0.x) before an
// instruction (vs_2_x on); _sat on an instruction; defi i#, n, n, n, n and defb b#, true|false; relative
// operands indexed by a0 with any swizzle (c0[a0.y], c0[a0] = .xyzw) or aL; vs_3_0's o# outputs, dcl on
// o# and s# (dcl_2d, dcl_cube, dcl_volume), v#[aL], o[a0.x + n] and r#_abs. A register the model does
// not have (v16, o12, s4, r12 in vs_2_0) is a syntax error there, as in Microsoft's assembler, except on
// a relative operand; vs_1_1 leaves register ranges to the validator.
//
// Every error carries the file, line and column it comes from, and parsing goes on with the next
// line, so one run reports many errors.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "vm/asm/preprocessor.h"
#include "vm/core/diagnostic.h"
#include "vm/core/isa.h"
#include "vm/core/program.h"

namespace vs11 {

struct AssembleOptions {
  PreprocessOptions preprocess;  // -I and -D
  bool validate = true;          // run the validator unless --skip-validation
  int constant_count = kDefaultConstantCount;
  bool require_position = true;  // false: validate a fragment that need not write oPos
  bool strict = false;           // DX8 reads of unwritten lanes are errors, not warnings (--strict)
};

struct AssembleResult {
  std::optional<Program> program;  // set when there are no errors (warnings allowed)
  Diagnostics diagnostics;
  bool dx9_syntax = false;  // the version line was spelled vs_1_1 / vs_1_0 (DX9), not vs.1.1
};

// Assembles `text`, which came from `file_name` (used in messages and to find #include files).
// With options.validate the validator runs when there were no syntax errors, with DX9 rules for a
// `vs_1_1` version line or a program with a dcl, and DX8 rules (no dcl needed) for a `vs.1.1` /
// `vs.1.0` program without one.
// program.source_locs[i] is where instruction i was written (the column of its mnemonic).
AssembleResult AssembleSource(std::string_view text, const std::string& file_name, const AssembleOptions& options,
                              const FileReader& reader = ReadFileFromDisk);

// Reads and assembles a file; an unreadable file gives an error diagnostic and no program.
AssembleResult AssembleFile(const std::filesystem::path& path, const AssembleOptions& options);

}  // namespace vs11
