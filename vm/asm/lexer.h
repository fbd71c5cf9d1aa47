// The lexical vocabulary of .vsh assembly text (spec §2): tokens of one preprocessed line, and the
// spellings that the assembler reads and the disassembler prints (register names, component letters).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "vm/asm/preprocessor.h"
#include "vm/core/diagnostic.h"
#include "vm/core/program.h"
#include "vm/core/register_names.h"

namespace vs11 {

enum class TokenKind {
  kIdentifier,  // letters, digits and '_', not starting with a digit: mov, r0, dcl_texcoord1, xyzw, vs_1_1
  kInteger,     // decimal digits: 12
  kFloat,       // 1.  .5  1.5  1e-3  1.0f  1f
  kComma,
  kDot,
  kLeftBracket,
  kRightBracket,
  kPlus,
  kMinus,
  kBang,       // '!' (a ps_2_x predicate modifier; recognised only to be rejected)
  kLeftParen,  // '(' and ')' (predicates; recognised only to be rejected)
  kRightParen,
};

struct Token {
  TokenKind kind = TokenKind::kIdentifier;
  std::string text;  // exactly as written
  int column = 0;    // 1-based source column of the first character
};

struct LexedLine {
  std::vector<Token> tokens;
  SourceLoc loc;  // file and line; column 1 (each token carries its own column)
};

// Splits one preprocessed line into tokens. A ';' or "//" ends the line (the preprocessor normally
// removes comments already). An unexpected character or a malformed number is reported in
// `diagnostics` and the line is returned cut at that point.
LexedLine Lex(const PreprocessedLine& line, Diagnostics& diagnostics);

// The location of `token` on `line`.
SourceLoc LocOf(const LexedLine& line, const Token& token);

// Version statements (§2.1 item 4). The DX9 spellings come first: the disassembler prints the first
// spelling of a version token.
struct VersionSpelling {
  std::string_view text;  // lower case, blanks removed
  std::uint32_t token;
  bool dx9;  // vs_1_1 (DX9: dcl required) rather than vs.1.1 (DX8)
};
inline constexpr std::array kVersionSpellings = {
    VersionSpelling{"vs_1_1", kVersionVs11, true},
    VersionSpelling{"vs_1_0", kVersionVs10, true},
    VersionSpelling{"vs.1.1", kVersionVs11, false},
    VersionSpelling{"vs.1.0", kVersionVs10, false},
    VersionSpelling{"vs_2_0", Info(ShaderModel::kVs20).version_token, true},
    VersionSpelling{"vs.2.0", Info(ShaderModel::kVs20).version_token, true},
    VersionSpelling{"vs_2_x", Info(ShaderModel::kVs2x).version_token, true},
    VersionSpelling{"vs.2.x", Info(ShaderModel::kVs2x).version_token, true},
    VersionSpelling{"vs_3_0", Info(ShaderModel::kVs30).version_token, true},
    VersionSpelling{"vs.3.0", Info(ShaderModel::kVs30).version_token, true},
};

// The text form of a register (no mask, swizzle or relative suffix): "r3", "oPos", "oT7". A register
// with no spelling (RASTOUT 3 and beyond) prints as "<register type 4 number 3>", which does not
// assemble; Decode refuses such registers (HasRegisterName).
std::string RegisterName(RegisterFile file, int index);
bool HasRegisterName(RegisterFile file, int index);
// As a program of `model` spells it: vs_3_0's outputs are o0-o11 (the oT file's type number).
std::string RegisterName(RegisterFile file, int index, ShaderModel model);

// Component letters: x y z w, with r g b a as synonyms (§2.3). Returns the lane 0-3, or -1.
int LaneFromLetter(char letter);

// The register that a relative constant is indexed by, as written in §2.2 and printed by the
// disassembler: c<n>[a0.x].
inline constexpr std::string_view kAddressRegisterName = "a0";
inline constexpr int kAddressLane = 0;

bool EqualsIgnoringAsciiCase(std::string_view a, std::string_view b);
std::string ToLowerAscii(std::string_view text);

}  // namespace vs11
