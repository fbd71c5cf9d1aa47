#include "vm/asm/assembler.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <charconv>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "vm/asm/lexer.h"
#include "vm/asm/validator.h"
#include "vm/core/input_file.h"

namespace vs11 {
namespace {

// Instruction modifiers of later shader models (§2.6), written as mnemonic suffixes: mov_sat.
constexpr std::array<std::string_view, 9> kInstructionModifiers = {"sat", "pp", "centroid", "x2", "x4",
                                                                   "x8",  "d2", "d4",       "d8"};
// Source modifiers of pixel shaders and later models (§2.5), written as register suffixes: r0_abs.
constexpr std::array<std::string_view, 8> kSourceModifierSuffixes = {"abs", "bias", "bx2", "x2",
                                                                     "dz",  "dw",   "db",  "da"};
// Mnemonics of other shader models (§4.7), named so that they get "not a vs_1_1 instruction" rather
// than "unknown instruction".
constexpr std::array<std::string_view, 59> kOtherModelMnemonics = {
    "lrp",          "call",      "callnz",     "loop",       "ret",          "endloop",    "label",      "pow",
    "crs",          "sgn",       "abs",        "nrm",        "sincos",       "rep",        "endrep",     "if",
    "ifc",          "else",      "endif",      "break",      "breakc",       "mova",       "defb",       "defi",
    "texcoord",     "texcrd",    "texkill",    "tex",        "texld",        "texldp",     "texldb",     "texbem",
    "texbeml",      "texreg2ar", "texreg2gb",  "texm3x2pad", "texm3x2tex",   "texm3x3pad", "texm3x3tex", "texm3x3spec",
    "texm3x3vspec", "cnd",       "texreg2rgb", "texdp3tex",  "texm3x2depth", "texdp3",     "texm3x3",    "texdepth",
    "cmp",          "bem",       "dp2add",     "dsx",        "dsy",          "texldd",     "setp",       "texldl",
    "breakp",       "phase",     "dp2"};

template <std::size_t N>
bool Contains(const std::array<std::string_view, N>& list, std::string_view word) {
  return std::find(list.begin(), list.end(), word) != list.end();
}

// 2 bits per lane, lane x lowest: the packing Swizzle documents (vm/core/program.h).
Swizzle SwizzleFromSelectors(const std::array<int, 4>& selectors) {
  unsigned bits = 0;
  for (int lane = 3; lane >= 0; --lane) bits = bits * 4 + static_cast<unsigned>(selectors[lane]);
  return Swizzle(static_cast<std::uint8_t>(bits));
}

WriteMask MaskWithLane(WriteMask mask, int lane) {
  return WriteMask(static_cast<std::uint8_t>(mask.bits() | (1u << lane)));
}

// What each operand position of an instruction holds, from its operand shape (§3.2 "form").
enum class OperandKind { kDest, kSource, kFloat, kInteger, kBool };

std::vector<OperandKind> OperandKinds(const OpcodeInfo& info, ShaderModel model) {
  constexpr int kDefValues = 4;
  std::vector<OperandKind> kinds;
  if (info.has_dest()) kinds.push_back(OperandKind::kDest);
  if (info.shape == OperandShape::kDefinition) {
    kinds.insert(kinds.end(), kDefValues, OperandKind::kFloat);
  } else if (info.shape == OperandShape::kIntDefinition) {
    kinds.insert(kinds.end(), kDefValues, OperandKind::kInteger);
  } else if (info.shape == OperandShape::kBoolDefinition) {
    kinds.push_back(OperandKind::kBool);
  } else {
    kinds.insert(kinds.end(), SourceCount(info, model), OperandKind::kSource);
  }
  return kinds;
}

std::string FormText(const std::vector<OperandKind>& kinds) {
  constexpr std::array<std::string_view, 5> kNames = {"dest", "src", "float", "int", "bool"};
  std::string text;
  for (OperandKind kind : kinds) {
    if (!text.empty()) text += ", ";
    text += kNames[static_cast<int>(kind)];
  }
  return text;
}

// The opcodes whose mnemonic takes a comparison suffix: if_gt, break_ne, setp_le.
constexpr std::array kComparisonOpcodes = {Opcode::kIfc, Opcode::kBreakc, Opcode::kSetp};

// Walks the tokens of one operand (or one statement).
class Cursor {
 public:
  Cursor(std::span<const Token> tokens, int end_column) : tokens_(tokens), end_column_(end_column) {}

  bool AtEnd() const { return pos_ >= tokens_.size(); }
  bool NextIs(TokenKind kind, std::size_t ahead = 0) const {
    return pos_ + ahead < tokens_.size() && tokens_[pos_ + ahead].kind == kind;
  }
  const Token& Peek() const { return tokens_[pos_]; }
  const Token& Next() { return tokens_[pos_++]; }
  bool Accept(TokenKind kind) {
    if (!NextIs(kind)) return false;
    ++pos_;
    return true;
  }
  // Column of the next token, or just past the last one.
  int column() const { return AtEnd() ? end_column_ : tokens_[pos_].column; }

 private:
  std::span<const Token> tokens_;
  int end_column_;
  std::size_t pos_ = 0;
};

int ColumnAfter(const Token& token) { return token.column + static_cast<int>(token.text.size()); }

// Parses one statement (one lexed line). Each Parse* function reports its first error and returns
// false; the caller then abandons the line.
class StatementParser {
 public:
  StatementParser(const LexedLine& line, ShaderModel model, Diagnostics& diagnostics)
      : line_(line), model_(model), diagnostics_(diagnostics) {}

  bool ParseInstruction(Instruction& instruction) {
    std::span<const Token> tokens = line_.tokens;
    const Token& start = tokens.front();
    if (start.kind == TokenKind::kPlus) {
      return Fail(start, DiagnosticCode::kNotInVs11,
                  "co-issue ('+' before an instruction) is not available in vertex shaders");
    }
    if (start.kind == TokenKind::kLeftParen) {
      if (!RegisterCount(RegisterFile::kPredicate, model_)) {
        return Fail(start, NotInModelCode(), fmt::format("predication ('(p0)') is not available in {}", ModelName()));
      }
      if (!ParsePredicate(tokens, instruction)) return false;
    }
    const Token& first = tokens.front();
    if (first.kind != TokenKind::kIdentifier)
      return Fail(first, DiagnosticCode::kUnexpectedToken,
                  fmt::format("expected an instruction, found '{}'", first.text));
    if (!ParseMnemonic(first, instruction)) return false;
    if (instruction.predicated && !instruction.info().is_executable()) {
      return Fail(start, DiagnosticCode::kPredicateSyntax,
                  fmt::format("{} cannot be predicated", instruction.info().mnemonic));
    }
    std::vector<std::span<const Token>> operands;
    if (!SplitOperands(tokens.subspan(1), operands)) return false;
    // Operands are parsed before the count is checked, so that `mov r0 r1` points at the stray r1.
    std::vector<OperandKind> kinds = OperandKinds(instruction.info(), model_);
    int source = 0;
    int value = 0;
    for (std::size_t i = 0; i < std::min(kinds.size(), operands.size()); ++i) {
      Cursor cursor(operands[i], ColumnAfter(operands[i].back()));
      bool ok = false;
      switch (kinds[i]) {
        case OperandKind::kDest:
          ok = ParseDest(cursor, WriteMask(instruction.info().default_mask), instruction.dest);
          break;
        case OperandKind::kSource: ok = ParseSource(cursor, instruction.sources[source++]); break;
        case OperandKind::kFloat: ok = ParseFloat(cursor, instruction.def_bits[value++]); break;
        case OperandKind::kInteger: ok = ParseInteger(cursor, instruction.def_bits[value++]); break;
        case OperandKind::kBool: ok = ParseBool(cursor, instruction.def_bits[value++]); break;
      }
      if (!ok) return false;
    }
    if (operands.size() != kinds.size()) {
      return Fail(first, DiagnosticCode::kOperandCount,
                  fmt::format("{} takes {} operand{}{}, found {}", instruction.info().mnemonic, kinds.size(),
                                     kinds.size() == 1 ? "" : "s",
                                     kinds.empty() ? "" : fmt::format(" ({})", FormText(kinds)), operands.size()));
    }
    return true;
  }

 private:
  // Records an error at `column` of this line; returns false so that callers can `return Fail(...)`.
  bool Fail(int column, DiagnosticCode code, std::string message) {
    diagnostics_.Error(SourceLoc{line_.loc.file, line_.loc.line, column}, code, std::move(message));
    return false;
  }
  bool Fail(const Token& token, DiagnosticCode code, std::string message) {
    return Fail(token.column, code, std::move(message));
  }

  std::string_view ModelName() const { return ShaderModelName(model_); }
  bool Later() const { return model_ != ShaderModel::kVs11; }
  DiagnosticCode NotInModelCode() const { return Later() ? DiagnosticCode::kNotInModel : DiagnosticCode::kNotInVs11; }

  // `(p0)`, `(!p0.x)` before an instruction (vs_2_x on); `tokens` is left at the instruction.
  bool ParsePredicate(std::span<const Token>& tokens, Instruction& instruction) {
    std::size_t close = 1;
    while (close < tokens.size() && tokens[close].kind != TokenKind::kRightParen) ++close;
    if (close == tokens.size() || close == 1) {
      return Fail(tokens.front(), DiagnosticCode::kPredicateSyntax, "expected (p0) or (!p0) before the instruction");
    }
    Cursor cursor(tokens.subspan(1, close - 1), tokens[close].column);
    const int column = cursor.column();
    if (!ParseSource(cursor, instruction.predicate)) return false;
    if (instruction.predicate.reg.file != RegisterFile::kPredicate || instruction.predicate.negate ||
        instruction.predicate.absolute) {
      return Fail(column, DiagnosticCode::kPredicateSyntax, "an instruction is predicated on p0 or !p0 only");
    }
    if (close + 1 == tokens.size()) {
      return Fail(ColumnAfter(tokens[close]), DiagnosticCode::kUnexpectedToken, "expected an instruction after the predicate");
    }
    instruction.predicated = true;
    tokens = tokens.subspan(close + 1);
    return true;
  }

  // `opcode` exists in the program's model, or an error naming the model that has it.
  bool CheckOpcodeModel(const Token& token, Opcode opcode) {
    const OpcodeInfo& info = Info(opcode);
    if (OpcodeAllowed(info, model_)) return true;
    if (!Later()) return Fail(token, DiagnosticCode::kNotInVs11, fmt::format("'{}' is not a vs_1_1 instruction", token.text));
    return Fail(token, DiagnosticCode::kNotInModel, fmt::format("'{}' is not a {} instruction (it exists from {} on)",
                                                                token.text, ModelName(), ShaderModelName(info.since)));
  }

  // if_gt, break_ne, setp_le, and the _sat instruction modifier of later models.
  std::optional<bool> ParseSuffixedMnemonic(const Token& token, std::string_view stem, std::string_view suffix,
                                            Instruction& instruction) {
    if (std::optional<int> comparison = ComparisonFromName(suffix)) {
      for (Opcode opcode : kComparisonOpcodes) {
        if (ComparisonStem(opcode) != stem) continue;
        instruction.opcode = opcode;
        instruction.comparison = *comparison;
        return CheckOpcodeModel(token, opcode);
      }
    }
    std::optional<Opcode> opcode = OpcodeFromMnemonic(stem);
    if (Later() && suffix == "sat" && opcode && Info(*opcode).has_dest() && Info(*opcode).is_executable() &&
        !TakesComparison(*opcode)) {
      instruction.opcode = *opcode;
      instruction.dest.saturate = true;
      return CheckOpcodeModel(token, *opcode);
    }
    return std::nullopt;
  }

  bool ParseMnemonic(const Token& token, Instruction& instruction) {
    std::string name = ToLowerAscii(token.text);
    constexpr std::string_view kDclPrefix = "dcl_";
    if (name.starts_with(kDclPrefix)) {
      instruction.opcode = Opcode::kDcl;
      std::string_view rest = std::string_view(name).substr(kDclPrefix.size());
      if (std::optional<int> sampler = SamplerTypeFromName(rest); sampler && RegisterCount(RegisterFile::kSampler, model_)) {
        instruction.sampler_type = *sampler;
        return true;
      }
      return ParseDclUsage(token, rest, instruction);
    }
    if (std::optional<Opcode> opcode = OpcodeFromMnemonic(name);
        opcode && *opcode != Opcode::kDcl && !TakesComparison(*opcode)) {
      instruction.opcode = *opcode;
      return CheckOpcodeModel(token, *opcode);
    }
    if (name == Info(Opcode::kDcl).mnemonic) {
      return Fail(token, DiagnosticCode::kDeclarationUsage, "dcl needs a usage, as in dcl_position or dcl_texcoord1");
    }
    std::size_t underscore = name.find('_');
    if (underscore != std::string::npos) {
      std::string_view stem = std::string_view(name).substr(0, underscore);
      std::string_view suffix = std::string_view(name).substr(underscore + 1);
      if (std::optional<bool> ok = ParseSuffixedMnemonic(token, stem, suffix, instruction)) return *ok;
      if (OpcodeFromMnemonic(stem) && Contains(kInstructionModifiers, suffix)) {
        return Fail(token, NotInModelCode(), fmt::format("instruction modifier '{}' is not available in {}",
                                                         token.text.substr(underscore), Later() ? "vertex shaders" : "vs_1_1"));
      }
    }
    if (std::optional<Opcode> opcode = OpcodeFromMnemonic(name); opcode && TakesComparison(*opcode)) {
      if (!OpcodeAllowed(Info(*opcode), model_)) return CheckOpcodeModel(token, *opcode);
      return Fail(token, DiagnosticCode::kUnknownInstruction,
                  fmt::format("'{}' needs a comparison: {}_gt, _eq, _ge, _lt, _ne or _le", token.text,
                              ComparisonStem(*opcode)));
    }
    if (Contains(kOtherModelMnemonics, name)) {
      return Fail(token, NotInModelCode(), fmt::format("'{}' is not a {} instruction", token.text, ModelName()));
    }
    return Fail(token, DiagnosticCode::kUnknownInstruction, fmt::format("unknown instruction '{}'", token.text));
  }

  // dcl_<usage>[index]: `rest` is what follows "dcl_", in lower case.
  bool ParseDclUsage(const Token& token, std::string_view rest, Instruction& instruction) {
    std::size_t digits = rest.size();
    while (digits > 0 && std::isdigit(static_cast<unsigned char>(rest[digits - 1]))) --digits;
    std::optional<int> usage = DeclUsageFromName(rest.substr(0, digits));
    if (!usage) return Fail(token, DiagnosticCode::kDeclarationUsage,
                            fmt::format("unknown dcl usage '{}'", rest.substr(0, digits)));
    instruction.usage = *usage;
    instruction.usage_index = 0;
    if (digits < rest.size()) {
      std::string_view index = rest.substr(digits);
      auto [ptr, ec] = std::from_chars(index.data(), index.data() + index.size(), instruction.usage_index);
      if (ec != std::errc() || instruction.usage_index > kMaxDeclUsageIndex) {
        return Fail(token, DiagnosticCode::kDeclarationUsage,
                    fmt::format("dcl usage index {} is out of range 0-{}", index, kMaxDeclUsageIndex));
      }
    }
    return true;
  }

  bool SplitOperands(std::span<const Token> tokens, std::vector<std::span<const Token>>& operands) {
    std::size_t begin = 0;
    for (std::size_t i = 0; i <= tokens.size(); ++i) {
      if (i < tokens.size() && tokens[i].kind != TokenKind::kComma) continue;
      if (i == begin) {
        if (i == tokens.size() && operands.empty()) return true;  // no operands at all
        int column = i < tokens.size() ? tokens[i].column : ColumnAfter(tokens[i - 1]);
        return Fail(column, DiagnosticCode::kOperandCount, "missing operand");
      }
      operands.push_back(tokens.subspan(begin, i - begin));
      begin = i + 1;
    }
    return true;
  }

  bool ExpectEnd(const Cursor& cursor, std::string_view what) {
    if (cursor.AtEnd()) return true;
    return Fail(cursor.Peek(), DiagnosticCode::kUnexpectedToken,
                fmt::format("unexpected '{}' after the {}", cursor.Peek().text, what));
  }

  // A written mask is emitted as written, on every register (Microsoft's assembler keeps
  // `mov oFog.x, r0.x` as mask .x); without one the opcode's default mask applies (vm/core/isa.h).
  bool ParseDest(Cursor& cursor, WriteMask default_mask, DestOperand& dest) {
    if (cursor.NextIs(TokenKind::kMinus)) return Fail(cursor.Peek(), DiagnosticCode::kDestinationSyntax,
                                                      "a destination cannot be negated");
    int column = cursor.column();
    if (!ParseRegister(cursor, dest.reg)) return false;
    const bool relative_output = model_ >= ShaderModel::kVs30 && dest.reg.file == RegisterFile::kTexCoordOut;
    if (dest.reg.relative && !relative_output) {
      return Fail(column, DiagnosticCode::kDestinationSyntax,
                  Later() ? fmt::format("a destination cannot be relatively addressed in {} (vs_3_0: o# only)", ModelName())
                          : std::string("a destination cannot be relatively addressed"));
    }
    if (!CheckRegisterExists(column, dest.reg)) return false;
    dest.mask = default_mask;
    if (cursor.Accept(TokenKind::kDot) && !ParseWriteMask(cursor, dest.mask)) return false;
    return ExpectEnd(cursor, "destination");
  }

  bool ParseSource(Cursor& cursor, SourceOperand& source) {
    source.negate = cursor.Accept(TokenKind::kMinus);
    if (source.negate && cursor.NextIs(TokenKind::kMinus)) return Fail(cursor.Peek(), DiagnosticCode::kSourceModifier,
                                                                       "double negation");
    if (cursor.NextIs(TokenKind::kBang)) {
      if (!Later() || source.negate) {
        return Fail(cursor.Peek(), DiagnosticCode::kSourceModifier,
                    fmt::format("the '!' source modifier is not available {}",
                                Later() ? "with negation" : "in vs_1_1 (only negation)"));
      }
      cursor.Next();
      source.logical_not = true;
    }
    if (cursor.NextIs(TokenKind::kInteger) && cursor.NextIs(TokenKind::kMinus, 1)) {
      return Fail(cursor.Peek(), DiagnosticCode::kSourceModifier,
                  fmt::format("the complement source modifier '1-' is not available in {} (only negation{})",
                              Later() ? "vertex shaders" : "vs_1_1", model_ >= ShaderModel::kVs30 ? " and _abs" : ""));
    }
    if (cursor.NextIs(TokenKind::kInteger) || cursor.NextIs(TokenKind::kFloat)) {
      return Fail(cursor.Peek(), DiagnosticCode::kExpectedRegister,
                  fmt::format("a source must be a register, not the number '{}' (use def)", cursor.Peek().text));
    }
    const int column = cursor.column();
    absolute_ = false;
    if (!ParseRegister(cursor, source.reg)) return false;
    source.absolute = absolute_;
    if (!CheckRegisterExists(column, source.reg)) return false;
    source.swizzle = Swizzle();
    if (cursor.Accept(TokenKind::kDot) && !ParseSwizzle(cursor, source.swizzle)) return false;
    return ExpectEnd(cursor, "source");
  }

  // r7, oPos, c[...], c4[...]: the name, then for constants an optional bracketed index.
  bool ParseRegister(Cursor& cursor, RegisterRef& reg) {
    if (cursor.AtEnd()) return Fail(cursor.column(), DiagnosticCode::kExpectedRegister, "expected a register");
    const Token& name = cursor.Next();
    if (name.kind != TokenKind::kIdentifier) {
      return Fail(name, DiagnosticCode::kExpectedRegister, fmt::format("expected a register, found '{}'", name.text));
    }
    bool has_number = false;
    if (!ResolveRegisterName(name, reg, has_number)) return false;
    if (cursor.NextIs(TokenKind::kLeftBracket)) {
      const Token& bracket = cursor.Next();
      const bool indexable = reg.file == RegisterFile::kConst ||
                             (model_ >= ShaderModel::kVs30 &&
                              (reg.file == RegisterFile::kInput || reg.file == RegisterFile::kTexCoordOut));
      if (!indexable) {
        return Fail(bracket, DiagnosticCode::kConstantIndexSyntax,
                    fmt::format("only {} registers can be indexed with [...] in {}, not '{}'",
                                model_ >= ShaderModel::kVs30 ? "constant, input and output" : "constant", ModelName(),
                                name.text));
      }
      return ParseConstantIndex(cursor, bracket, reg);
    }
    if (!has_number) return Fail(name, DiagnosticCode::kUnknownRegister,
                                 fmt::format("register '{}' needs a number", name.text));
    return true;
  }

  // Splits "oT3" into a spelling from kRegisterSpellings and its number.
  bool ResolveRegisterName(const Token& name, RegisterRef& reg, bool& has_number) {
    std::string_view text = name.text;
    std::size_t letters = 0;
    while (letters < text.size() && std::isalpha(static_cast<unsigned char>(text[letters]))) ++letters;
    std::size_t digits = letters;
    while (digits < text.size() && std::isdigit(static_cast<unsigned char>(text[digits]))) ++digits;
    std::string_view rest = text.substr(digits);
    if (model_ >= ShaderModel::kVs30 && EqualsIgnoringAsciiCase(rest, "_abs")) {
      absolute_ = true;
      rest = {};
      text = text.substr(0, digits);
    } else if (rest.starts_with('_') && Contains(kSourceModifierSuffixes, ToLowerAscii(rest.substr(1)))) {
      return Fail(name, DiagnosticCode::kSourceModifier,
                  fmt::format("source modifier '{}' is not available in {} (only negation{})", rest, ModelName(),
                              Later() ? "; _abs from vs_3_0 on" : ""));
    }
    auto spelling = std::find_if(kRegisterSpellings.begin(), kRegisterSpellings.end(), [&](const auto& s) {
      return EqualsIgnoringAsciiCase(s.name, text.substr(0, letters));
    });
    // vs_3_0 names its outputs o#, the earlier models oPos, oFog, oPts, oD#, oT#.
    if (spelling != kRegisterSpellings.end() && IsOutput(spelling->file) &&
        (spelling->name == kVs30OutputSpelling) != (model_ >= ShaderModel::kVs30)) {
      spelling = kRegisterSpellings.end();
    }
    bool fixed = spelling != kRegisterSpellings.end() && spelling->fixed_index != RegisterSpelling::kNumbered;
    if (spelling == kRegisterSpellings.end() || !rest.empty() || (fixed && digits > letters)) {
      return Fail(name, DiagnosticCode::kUnknownRegister, fmt::format("unknown register '{}'", text));
    }
    reg = RegisterRef{spelling->file, fixed ? spelling->fixed_index : 0, false};
    has_number = fixed || digits > letters;
    if (fixed || digits == letters) return true;
    return ParseRegisterNumber(name, text.substr(letters, digits - letters), reg.index);
  }

  bool ParseRegisterNumber(const Token& token, std::string_view digits, int& number) {
    long long value = 0;
    auto [ptr, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
    if (ec != std::errc() || value > kMaxConstantIndex) {
      return Fail(token, DiagnosticCode::kRegisterNumberTooLarge,
                  fmt::format("register number {} does not fit the 11-bit register field (0-{})", digits,
                                     kMaxConstantIndex));
    }
    number = static_cast<int>(value);
    return true;
  }

  // After "c[" or "c<n>[": integers and at most one a0.x joined by + and -, then "]" (§2.2).
  bool ParseConstantIndex(Cursor& cursor, const Token& bracket, RegisterRef& reg) {
    long long total = reg.index;
    int sign = 1;
    bool expect_term = true;
    bool first = true;
    while (true) {
      if (cursor.AtEnd()) return Fail(cursor.column(), DiagnosticCode::kConstantIndexSyntax,
                                      "missing ']' after the constant index");
      const Token& token = cursor.Next();
      if (!expect_term) {
        if (token.kind == TokenKind::kRightBracket) break;
        if (token.kind != TokenKind::kPlus && token.kind != TokenKind::kMinus) {
          return Fail(token, DiagnosticCode::kConstantIndexSyntax,
                      fmt::format("expected '+', '-' or ']' in the constant index, found '{}'", token.text));
        }
        sign = token.kind == TokenKind::kMinus ? -1 : 1;
        expect_term = true;
        continue;
      }
      if (first && (token.kind == TokenKind::kMinus || token.kind == TokenKind::kPlus)) {
        sign = token.kind == TokenKind::kMinus ? -1 : 1;
        first = false;
        continue;
      }
      first = false;
      if (token.kind == TokenKind::kInteger) {
        int value = 0;
        if (!ParseRegisterNumber(token, token.text, value)) return false;
        total += sign * value;
      } else if (token.kind == TokenKind::kIdentifier && Later() &&
                 (EqualsIgnoringAsciiCase(token.text, kAddressRegisterName) ||
                  (EqualsIgnoringAsciiCase(token.text, RegisterName(RegisterFile::kLoop, 0)) &&
                   RegisterCount(RegisterFile::kLoop, model_)))) {
        if (!ParseAddressRegister(cursor, token, sign, reg)) return false;
      } else if (token.kind == TokenKind::kIdentifier && EqualsIgnoringAsciiCase(token.text, kAddressRegisterName)) {
        if (!ParseAddressLane(cursor, token, sign, reg.relative)) return false;
      } else if (token.kind == TokenKind::kFloat) {
        return Fail(token, DiagnosticCode::kConstantIndexSyntax,
                    fmt::format("a constant index must be an integer, not '{}'", token.text));
      } else if (token.kind == TokenKind::kRightBracket) {
        return Fail(token, DiagnosticCode::kConstantIndexSyntax, "missing value in the constant index");
      } else {
        return Fail(token, DiagnosticCode::kConstantIndexSyntax,
                    fmt::format("a constant index may hold only integers and a0.x, not '{}'", token.text));
      }
      expect_term = false;
    }
    if (total < 0) return Fail(bracket, DiagnosticCode::kConstantIndexSyntax,
                               fmt::format("constant index {} is negative", total));
    if (total > kMaxConstantIndex) {
      return Fail(bracket, DiagnosticCode::kRegisterNumberTooLarge,
                  fmt::format("constant index {} does not fit the 11-bit register field (0-{})", total,
                                       kMaxConstantIndex));
    }
    reg.index = static_cast<int>(total);
    return true;
  }

  // After "a0" inside a constant index: ".x" (§1.5: `c0[a0]` is rejected by the native assembler).
  bool ParseAddressLane(Cursor& cursor, const Token& a0, int sign, bool& relative) {
    if (!cursor.Accept(TokenKind::kDot)) return Fail(a0, DiagnosticCode::kConstantIndexSyntax,
                                                     "relative addressing needs a0.x ('a0' alone is not accepted)");
    if (!cursor.NextIs(TokenKind::kIdentifier) || !EqualsIgnoringAsciiCase(cursor.Peek().text, "x")) {
      return Fail(cursor.column(), DiagnosticCode::kConstantIndexSyntax, "only a0.x can index constants");
    }
    cursor.Next();
    if (sign < 0) return Fail(a0, DiagnosticCode::kConstantIndexSyntax,
                              "a0.x cannot be subtracted in a constant index");
    if (relative) return Fail(a0, DiagnosticCode::kConstantIndexSyntax, "a0.x appears twice in the constant index");
    relative = true;
    return true;
  }

  // Later models: a0 with any swizzle (a0 alone: .xyzw, as Microsoft's assembler writes it) or aL.
  bool ParseAddressRegister(Cursor& cursor, const Token& name, int sign, RegisterRef& reg) {
    if (sign < 0) return Fail(name, DiagnosticCode::kConstantIndexSyntax,
                              fmt::format("{} cannot be subtracted in an index", name.text));
    if (reg.relative) return Fail(name, DiagnosticCode::kConstantIndexSyntax, "an index holds one address register");
    reg.relative = true;
    const bool loop = !EqualsIgnoringAsciiCase(name.text, kAddressRegisterName);
    Swizzle swizzle;
    if (cursor.Accept(TokenKind::kDot) && !ParseSwizzle(cursor, swizzle)) return false;
    if (loop && !swizzle.is_identity()) {
      return Fail(name, DiagnosticCode::kConstantIndexSyntax, "aL takes no swizzle in an index");
    }
    reg.address = AddressRegister{loop ? RegisterFile::kLoop : RegisterFile::kAddress, swizzle.bits()};
    return true;
  }

  // Later models: a register the model does not have is a syntax error, as in Microsoft's assembler
  // (constants are the validator's question: the bank's size is the device's; relative operands are
  // not checked). vs_1_1 leaves every register to the validator.
  bool CheckRegisterExists(int column, const RegisterRef& reg) {
    const bool later_only_file = reg.file == RegisterFile::kSampler || reg.file == RegisterFile::kLabel;
    if ((!Later() && !later_only_file) || reg.relative || reg.file == RegisterFile::kConst) return true;
    const int count = RegisterCount(reg.file, model_);
    if (reg.index < count) return true;
    return Fail(column, DiagnosticCode::kNoSuchRegister,
                count == 0 ? fmt::format("{} has no {} registers", ModelName(), RegisterName(reg.file, 0, model_))
                           : fmt::format("{} has no register {} (there are {})", ModelName(),
                                         RegisterName(reg.file, reg.index, model_), count));
  }

  // One defi value: a 32-bit signed integer.
  bool ParseInteger(Cursor& cursor, std::uint32_t& bits) {
    const bool negative = cursor.Accept(TokenKind::kMinus);
    if (!cursor.NextIs(TokenKind::kInteger)) {
      return Fail(cursor.column(), DiagnosticCode::kExpectedNumber,
                  cursor.AtEnd() ? std::string("expected an integer")
                                 : fmt::format("expected an integer, found '{}'", cursor.Peek().text));
    }
    const Token& token = cursor.Next();
    long long value = 0;
    auto [ptr, ec] = std::from_chars(token.text.data(), token.text.data() + token.text.size(), value);
    if (negative) value = -value;
    if (ec != std::errc() || value < INT32_MIN || value > INT32_MAX) {
      return Fail(token, DiagnosticCode::kNumberOutOfRange, fmt::format("'{}' is not a 32-bit integer", token.text));
    }
    bits = static_cast<std::uint32_t>(static_cast<std::int32_t>(value));
    return ExpectEnd(cursor, "integer");
  }

  // The defb value: true or false.
  bool ParseBool(Cursor& cursor, std::uint32_t& bits) {
    const bool word = cursor.NextIs(TokenKind::kIdentifier) &&
                      (EqualsIgnoringAsciiCase(cursor.Peek().text, "true") ||
                       EqualsIgnoringAsciiCase(cursor.Peek().text, "false"));
    if (!word) return Fail(cursor.column(), DiagnosticCode::kExpectedNumber, "expected true or false");
    bits = EqualsIgnoringAsciiCase(cursor.Next().text, "true") ? 1u : 0u;
    return ExpectEnd(cursor, "boolean");
  }

  bool ParseWriteMask(Cursor& cursor, WriteMask& mask) {
    if (!cursor.NextIs(TokenKind::kIdentifier)) {
      return Fail(cursor.column(), DiagnosticCode::kWriteMaskSyntax, cursor.AtEnd()
                                       ? std::string("empty write mask after '.'")
                                       : fmt::format("expected write mask letters, found '{}'", cursor.Peek().text));
    }
    const Token& letters = cursor.Next();
    mask = WriteMask(0);
    int last = -1;
    for (char letter : letters.text) {
      int lane = LaneFromLetter(letter);
      if (lane < 0) return Fail(letters, DiagnosticCode::kWriteMaskSyntax,
                                fmt::format("'{}' is not a write mask letter (xyzw or rgba)", letter));
      if (mask.has(lane)) return Fail(letters, DiagnosticCode::kWriteMaskSyntax,
                                      fmt::format("write mask '{}' repeats a component", letters.text));
      if (lane < last) {
        return Fail(letters, DiagnosticCode::kWriteMaskSyntax,
                    fmt::format("write mask '{}' is not in xyzw order", letters.text));
      }
      mask = MaskWithLane(mask, lane);
      last = lane;
    }
    return true;
  }

  bool ParseSwizzle(Cursor& cursor, Swizzle& swizzle) {
    constexpr std::size_t kLanes = 4;
    if (!cursor.NextIs(TokenKind::kIdentifier)) {
      return Fail(cursor.column(), DiagnosticCode::kSwizzleSyntax, cursor.AtEnd()
                                       ? std::string("empty swizzle after '.'")
                                       : fmt::format("expected swizzle letters, found '{}'", cursor.Peek().text));
    }
    const Token& letters = cursor.Next();
    std::string_view text = letters.text;
    if (std::size_t underscore = text.find('_');
        underscore != std::string_view::npos &&
        Contains(kSourceModifierSuffixes, ToLowerAscii(text.substr(underscore + 1)))) {
      return Fail(letters, DiagnosticCode::kSourceModifier,
                  fmt::format("source modifier '{}' is not available in vs_1_1 (only negation)",
                                       text.substr(underscore)));
    }
    if (text.size() > kLanes) return Fail(letters, DiagnosticCode::kSwizzleSyntax,
                                          fmt::format("swizzle '{}' has more than four components", text));
    std::array<int, kLanes> selectors{};
    for (std::size_t i = 0; i < kLanes; ++i) {
      // §2.4: fewer than four letters repeat the last one.
      char letter = text[std::min(i, text.size() - 1)];
      selectors[i] = LaneFromLetter(letter);
      if (selectors[i] < 0) return Fail(letters, DiagnosticCode::kSwizzleSyntax,
                                        fmt::format("'{}' is not a swizzle letter (xyzw or rgba)", letter));
    }
    swizzle = SwizzleFromSelectors(selectors);
    return true;
  }

  // One def value: [+|-] number | nan | inf (§2.1 item 6), stored as raw IEEE bits.
  bool ParseFloat(Cursor& cursor, std::uint32_t& bits) {
    bool negative = false;
    if (cursor.NextIs(TokenKind::kMinus) || cursor.NextIs(TokenKind::kPlus)) {
      negative = cursor.Next().kind == TokenKind::kMinus;
    }
    if (cursor.AtEnd()) return Fail(cursor.column(), DiagnosticCode::kExpectedNumber, "expected a number");
    const Token& token = cursor.Next();
    if (token.kind == TokenKind::kIdentifier && EqualsIgnoringAsciiCase(token.text, "nan")) {
      bits = kQuietNanBits;
    } else if (token.kind == TokenKind::kIdentifier && EqualsIgnoringAsciiCase(token.text, "inf")) {
      bits = kInfinityBits;
    } else if (token.kind == TokenKind::kInteger || token.kind == TokenKind::kFloat) {
      if (!ParseFloatBits(token, bits)) return false;
    } else {
      return Fail(token, DiagnosticCode::kExpectedNumber, fmt::format("expected a number, found '{}'", token.text));
    }
    if (negative) bits ^= kFloatSignBit;
    return ExpectEnd(cursor, "number");
  }

  bool ParseFloatBits(const Token& token, std::uint32_t& bits) {
    std::string_view text = token.text;
    if (text.ends_with('f') || text.ends_with('F')) text.remove_suffix(1);
    float value = 0;
    auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec == std::errc::result_out_of_range) {
      double wide = 0;
      std::from_chars(text.data(), text.data() + text.size(), wide);
      if (wide > 1) return Fail(token, DiagnosticCode::kNumberOutOfRange,
                                fmt::format("'{}' is too large for a 32-bit float", token.text));
      diagnostics_.Warning(SourceLoc{line_.loc.file, line_.loc.line, token.column}, DiagnosticCode::kNumberUnderflow,
                           fmt::format("'{}' is too small for a 32-bit float and becomes 0", token.text));
      value = 0;
    } else if (ec != std::errc() || ptr != text.data() + text.size()) {
      return Fail(token, DiagnosticCode::kMalformedNumber, fmt::format("malformed number '{}'", token.text));
    }
    bits = std::bit_cast<std::uint32_t>(value);
    return true;
  }

  const LexedLine& line_;
  ShaderModel model_;
  Diagnostics& diagnostics_;
  bool absolute_ = false;  // the register just parsed carried _abs (vs_3_0)
};

// A version statement as written: "vs_1_1" is one token, "vs.1.1" three (vs . 1.1).
struct VersionStatement {
  std::string text;  // lower case: "vs_1_1", "vs.1.1", "ps_2_0", ...
  std::size_t token_count = 0;
};

// The version statement that starts `line`, when the line is one (it names a vs or ps version).
std::optional<VersionStatement> FindVersionStatement(const LexedLine& line) {
  const std::vector<Token>& tokens = line.tokens;
  if (tokens.front().kind != TokenKind::kIdentifier) return std::nullopt;
  std::string name = ToLowerAscii(tokens.front().text);
  if (!name.starts_with("vs") && !name.starts_with("ps")) return std::nullopt;
  if (name.size() > 2 && name[2] == '_') return VersionStatement{name, 1};
  bool dotted = name.size() == 2 && tokens.size() >= 3 && tokens[1].kind == TokenKind::kDot &&
                (tokens[2].kind == TokenKind::kFloat || tokens[2].kind == TokenKind::kInteger);
  if (!dotted) return std::nullopt;
  return VersionStatement{name + "." + ToLowerAscii(tokens[2].text), 3};
}

class Assembler {
 public:
  explicit Assembler(AssembleResult& result) : result_(result) {}

  void Line(const PreprocessedLine& line) {
    int errors_before = result_.diagnostics.error_count();
    LexedLine lexed = Lex(line, result_.diagnostics);
    if (result_.diagnostics.error_count() != errors_before) {
      seen_statement_ = true;  // a line, if a bad one: do not also report a missing version
      return;
    }
    if (lexed.tokens.empty()) return;
    if (std::optional<VersionStatement> version = FindVersionStatement(lexed)) {
      ParseVersion(lexed, *version);
    } else {
      if (!seen_statement_) {
        result_.diagnostics.Error(LocOf(lexed, lexed.tokens.front()), DiagnosticCode::kVersionStatement,
                                  "the first statement must be the version (vs_1_1 or vs.1.1)");
      }
      Instruction instruction;
      if (StatementParser(lexed, program_.model(), result_.diagnostics).ParseInstruction(instruction)) {
        program_.instructions.push_back(instruction);
        program_.source_locs.push_back(LocOf(lexed, lexed.tokens.front()));
      }
    }
    seen_statement_ = true;
  }

  void Finish(const std::string& file_name) {
    if (!seen_statement_) {
      result_.diagnostics.Error(SourceLoc{file_name, 1, 1}, DiagnosticCode::kVersionStatement,
                                "missing version statement (vs_1_1 or vs.1.1)");
    }
  }

  Program& program() { return program_; }

 private:
  void ParseVersion(const LexedLine& line, const VersionStatement& version) {
    SourceLoc loc = LocOf(line, line.tokens.front());
    if (seen_statement_) {
      result_.diagnostics.Error(loc, DiagnosticCode::kVersionStatement,
                                "the version statement must come first and only once");
      return;
    }
    auto spelling = std::find_if(kVersionSpellings.begin(), kVersionSpellings.end(),
                                 [&](const VersionSpelling& v) { return v.text == version.text; });
    if (spelling == kVersionSpellings.end()) {
      result_.diagnostics.Error(
          loc, DiagnosticCode::kVersionStatement,
          fmt::format("unsupported shader version '{}' (expected vs_1_1, vs_2_0, vs_2_x, vs_3_0, vs.1.1 or vs.1.0)",
                      version.text));
      return;
    }
    if (line.tokens.size() > version.token_count) {
      const Token& extra = line.tokens[version.token_count];
      result_.diagnostics.Error(LocOf(line, extra), DiagnosticCode::kVersionStatement,
                                fmt::format("unexpected '{}' after the version", extra.text));
      return;
    }
    program_.version = spelling->token;
    result_.dx9_syntax = spelling->dx9;
  }

  AssembleResult& result_;
  Program program_;
  bool seen_statement_ = false;
};

}  // namespace

AssembleResult AssembleSource(std::string_view text, const std::string& file_name, const AssembleOptions& options,
                              const FileReader& reader) {
  AssembleResult result;
  PreprocessResult preprocessed = Preprocess(text, file_name, options.preprocess, reader);
  result.diagnostics.Append(preprocessed.diagnostics);
  Assembler assembler(result);
  for (const PreprocessedLine& line : preprocessed.lines) assembler.Line(line);
  assembler.Finish(file_name);
  if (result.diagnostics.HasErrors()) return result;
  if (options.validate) {
    ValidatorOptions validator_options;
    validator_options.constant_count = options.constant_count;
    validator_options.require_position = options.require_position;
    validator_options.strict = options.strict;
    // A vs.1.1 program with a dcl follows the dcl rules too: its tokens are those of a DX9 program, and
    // the same tokens loaded as bytecode (or disassembled, vm/asm/disassembler.h) get DX9 rules.
    validator_options.dialect = result.dx9_syntax ? ValidatorOptions::Dialect::kDx9 : ValidatorOptions::Dialect::kAuto;
    result.diagnostics.Append(Validate(assembler.program(), validator_options));
    if (result.diagnostics.HasErrors()) return result;
  }
  result.program = std::move(assembler.program());
  return result;
}

AssembleResult AssembleFile(const std::filesystem::path& path, const AssembleOptions& options) {
  Result<std::string> text = ReadInputFile(path, kMaxProgramFileBytes);
  if (!text) {
    AssembleResult result;
    result.diagnostics.Error(SourceLoc{InputDisplayName(path), 0, 0}, text.error().code, text.message());
    return result;
  }
  return AssembleSource(*text, InputDisplayName(path), options, ReadFileFromDisk);
}

}  // namespace vs11
