#include "vm/asm/lexer.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>

namespace vs11 {
namespace {

bool IsIdentifierStart(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
bool IsIdentifierChar(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }
bool IsDigit(char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }
bool IsBlank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

struct Punctuation {
  char c;
  TokenKind kind;
};
constexpr std::array kPunctuation = {
    Punctuation{',', TokenKind::kComma},       Punctuation{'.', TokenKind::kDot},
    Punctuation{'[', TokenKind::kLeftBracket}, Punctuation{']', TokenKind::kRightBracket},
    Punctuation{'+', TokenKind::kPlus},        Punctuation{'-', TokenKind::kMinus},
    Punctuation{'!', TokenKind::kBang},        Punctuation{'(', TokenKind::kLeftParen},
    Punctuation{')', TokenKind::kRightParen},
};

class LineLexer {
 public:
  LineLexer(const PreprocessedLine& line, Diagnostics& diagnostics)
      : text_(line.text), columns_(line.columns), diagnostics_(diagnostics) {
    out_.loc = SourceLoc{line.file, line.line, 1};
  }

  LexedLine Run() {
    while (pos_ < text_.size()) {
      char c = text_[pos_];
      if (IsBlank(c)) {
        ++pos_;
      } else if (c == ';' || text_.substr(pos_, 2) == "//") {
        break;  // comment to the end of the line
      } else if (IsIdentifierStart(c)) {
        LexIdentifier();
      } else if (LexVersion2x()) {
      } else if (StartsNumber()) {
        if (!LexNumber()) break;
      } else if (!LexPunctuation()) {
        Error(pos_, DiagnosticCode::kUnexpectedCharacter, fmt::format("unexpected character '{}'", c));
        break;
      }
    }
    return std::move(out_);
  }

 private:
  int ColumnAt(std::size_t pos) const { return pos < columns_.size() ? columns_[pos] : static_cast<int>(pos) + 1; }

  void Error(std::size_t pos, DiagnosticCode code, std::string message) {
    diagnostics_.Error(SourceLoc{out_.loc.file, out_.loc.line, ColumnAt(pos)}, code, std::move(message));
  }

  void Push(TokenKind kind, std::size_t begin) {
    out_.tokens.push_back(Token{kind, std::string(text_.substr(begin, pos_ - begin)), ColumnAt(begin)});
  }

  bool DigitAt(std::size_t pos) const { return pos < text_.size() && IsDigit(text_[pos]); }

  // A '.' starts a number (".5") unless it follows something a component suffix can follow
  // (r0.x, c[2].x, vs.1.1).
  bool StartsNumber() const {
    if (DigitAt(pos_)) return true;
    if (text_[pos_] != '.' || !DigitAt(pos_ + 1)) return false;
    if (out_.tokens.empty()) return true;
    TokenKind previous = out_.tokens.back().kind;
    return previous != TokenKind::kIdentifier && previous != TokenKind::kRightBracket &&
           previous != TokenKind::kInteger && previous != TokenKind::kFloat;
  }

  // The "2.x" of a `vs.2.x` version statement, which is no number: one token after `vs` `.`.
  bool LexVersion2x() {
    constexpr std::string_view kMinor = "2.x";
    if (out_.tokens.size() != 2 || out_.tokens[1].kind != TokenKind::kDot ||
        !EqualsIgnoringAsciiCase(out_.tokens[0].text, "vs") ||
        !EqualsIgnoringAsciiCase(text_.substr(pos_, kMinor.size()), kMinor) ||
        (pos_ + kMinor.size() < text_.size() && IsIdentifierChar(text_[pos_ + kMinor.size()]))) {
      return false;
    }
    const std::size_t begin = pos_;
    pos_ += kMinor.size();
    Push(TokenKind::kFloat, begin);
    return true;
  }

  void LexIdentifier() {
    std::size_t begin = pos_;
    while (pos_ < text_.size() && IsIdentifierChar(text_[pos_])) ++pos_;
    Push(TokenKind::kIdentifier, begin);
  }

  void SkipDigits() {
    while (DigitAt(pos_)) ++pos_;
  }

  // digits [ '.' digits ] [ e [+-] digits ] [ f ]   or   '.' digits [ e ... ] [ f ]
  bool LexNumber() {
    std::size_t begin = pos_;
    bool is_float = false;
    SkipDigits();
    if (pos_ < text_.size() && text_[pos_] == '.') {
      is_float = true;
      ++pos_;
      SkipDigits();
    }
    if (pos_ < text_.size() && (text_[pos_] == 'e' || text_[pos_] == 'E')) {
      std::size_t digits = pos_ + 1;
      if (digits < text_.size() && (text_[digits] == '+' || text_[digits] == '-')) ++digits;
      if (DigitAt(digits)) {
        is_float = true;
        pos_ = digits;
        SkipDigits();
      }
    }
    if (pos_ < text_.size() && (text_[pos_] == 'f' || text_[pos_] == 'F')) {
      is_float = true;
      ++pos_;
    }
    if (pos_ < text_.size() && (IsIdentifierChar(text_[pos_]) || text_[pos_] == '.')) {
      while (pos_ < text_.size() && (IsIdentifierChar(text_[pos_]) || text_[pos_] == '.')) ++pos_;
      Error(begin, DiagnosticCode::kMalformedNumber,
            fmt::format("malformed number '{}'", text_.substr(begin, pos_ - begin)));
      return false;
    }
    Push(is_float ? TokenKind::kFloat : TokenKind::kInteger, begin);
    return true;
  }

  bool LexPunctuation() {
    auto it = std::find_if(kPunctuation.begin(), kPunctuation.end(),
                           [&](const Punctuation& p) { return p.c == text_[pos_]; });
    if (it == kPunctuation.end()) return false;
    std::size_t begin = pos_++;
    Push(it->kind, begin);
    return true;
  }

  std::string_view text_;
  const std::vector<int>& columns_;
  Diagnostics& diagnostics_;
  std::size_t pos_ = 0;
  LexedLine out_;
};

}  // namespace

LexedLine Lex(const PreprocessedLine& line, Diagnostics& diagnostics) { return LineLexer(line, diagnostics).Run(); }

SourceLoc LocOf(const LexedLine& line, const Token& token) {
  return SourceLoc{line.loc.file, line.loc.line, token.column};
}

namespace {

const RegisterSpelling* FindSpelling(RegisterFile file, int index) {
  for (const RegisterSpelling& spelling : kRegisterSpellings) {
    if (spelling.file != file) continue;
    if (spelling.fixed_index == RegisterSpelling::kNumbered || spelling.fixed_index == index) return &spelling;
  }
  return nullptr;
}

}  // namespace

std::string RegisterName(RegisterFile file, int index) {
  const RegisterSpelling* spelling = FindSpelling(file, index);
  if (spelling == nullptr) return fmt::format("<register type {} number {}>", static_cast<int>(file), index);
  if (spelling->fixed_index == RegisterSpelling::kNumbered) return fmt::format("{}{}", spelling->name, index);
  return std::string(spelling->name);
}

bool HasRegisterName(RegisterFile file, int index) { return FindSpelling(file, index) != nullptr; }

std::string RegisterName(RegisterFile file, int index, ShaderModel model) {
  if (file == RegisterFile::kTexCoordOut && model >= ShaderModel::kVs30) {
    return fmt::format("{}{}", kVs30OutputSpelling, index);
  }
  return RegisterName(file, index);
}

int LaneFromLetter(char letter) {
  constexpr std::array<char, 4> kColorLetters = {'r', 'g', 'b', 'a'};  // §2.3: synonyms of x y z w
  char lower = static_cast<char>(std::tolower(static_cast<unsigned char>(letter)));
  for (int lane = 0; lane < 4; ++lane) {
    if (lower == kLaneLetters[lane] || lower == kColorLetters[lane]) return lane;
  }
  return -1;
}

bool EqualsIgnoringAsciiCase(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
         });
}

std::string ToLowerAscii(std::string_view text) {
  std::string out(text);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

}  // namespace vs11
