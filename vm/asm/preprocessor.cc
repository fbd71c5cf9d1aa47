#include "vm/asm/preprocessor.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <exception>
#include <fstream>
#include <iterator>
#include <limits>
#include <memory>
#include <set>
#include <unordered_map>

namespace vs11 {
namespace {

// Hostile input must not exhaust the stack, whatever the options say.
constexpr int kMaxExpansionDepth = 128;   // macro arguments pre-expanded inside macro arguments
constexpr int kMaxExpressionDepth = 256;  // parentheses, unary operators and ?: in #if
constexpr int kMaxIncludeDepthCap = 200;  // each #include level is a few stack frames
// Macro expansion and #include are charged "work" against max_output_bytes, so that expansions
// that produce nothing, or whose output is never emitted, are bounded as well. A token costs more
// than its text because its memory and handling do; the slack lets small limits expand small files.
constexpr std::size_t kTokenWork = 64;
constexpr std::size_t kWorkSlack = std::size_t{64} << 10;

bool IsSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }
bool IsDigit(char c) { return c >= '0' && c <= '9'; }
bool IsIdentStart(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; }
bool IsIdentChar(char c) { return IsIdentStart(c) || IsDigit(c); }

// Walks raw file text with line splices (backslash-newline) and the \r of CRLF made invisible,
// tracking the physical line and column of the current character.
class Cursor {
 public:
  explicit Cursor(std::string_view text) : text_(text) { SkipInvisible(); }
  bool AtEnd() const { return pos_ >= text_.size(); }
  char Get() const { return text_[pos_]; }
  int line() const { return line_; }
  int column() const { return column_; }
  char PeekNext() const {
    Cursor next = *this;
    next.Advance();
    return next.AtEnd() ? '\0' : next.Get();
  }
  void Advance() {
    if (AtEnd()) return;
    bool newline = text_[pos_++] == '\n';
    line_ += newline;
    column_ = newline ? 1 : column_ + 1;
    SkipInvisible();
  }

 private:
  void SkipInvisible() {
    while (pos_ < text_.size()) {
      bool crlf = text_[pos_] == '\r' && pos_ + 1 < text_.size() && text_[pos_ + 1] == '\n';
      if (crlf) ++pos_;
      if (crlf || text_[pos_] != '\\') return;
      // Blanks after the backslash are tolerated, as GCC does: editors do not show them.
      std::size_t end = pos_ + 1;
      while (end < text_.size() && (text_[end] == ' ' || text_[end] == '\t')) ++end;
      if (end < text_.size() && text_[end] == '\r') ++end;
      if (end >= text_.size() || text_[end] != '\n') return;
      pos_ = end + 1;
      ++line_;
      column_ = 1;
    }
  }

  std::string_view text_;
  std::size_t pos_ = 0;
  int line_ = 1;
  int column_ = 1;
};

struct LogicalLine {
  std::string text;
  std::vector<int> columns;  // source column of each character of text
  int line = 0;              // physical line of the first character
  int end_line = 0;          // physical line of the last one (later after splices)
};

// Splits a file into logical lines with comments replaced by a space. A /* */ comment spanning
// lines ends an ordinary line, so the instruction after it keeps its own line number for the
// assembler's messages, but it continues a directive as in C.
class LineSplitter {
 public:
  explicit LineSplitter(std::string_view text) : cursor_(text) {}
  bool Next(LogicalLine* out);
  bool in_comment() const { return in_comment_; }
  int comment_line() const { return comment_line_; }
  int comment_column() const { return comment_column_; }

 private:
  void Take(LogicalLine* out, char c) {
    if (blank_ && !IsSpace(c)) {
      blank_ = false;
      directive_ = c == '#';
    }
    out->text.push_back(c);
    out->columns.push_back(cursor_.column());
    cursor_.Advance();
  }

  Cursor cursor_;
  bool in_comment_ = false;
  int comment_line_ = 0;
  int comment_column_ = 0;
  bool blank_ = true;
  bool directive_ = false;
};

bool LineSplitter::Next(LogicalLine* out) {
  if (cursor_.AtEnd()) return false;
  out->text.clear();
  out->columns.clear();
  out->line = cursor_.line();
  blank_ = true;
  directive_ = false;
  while (!cursor_.AtEnd()) {
    char c = cursor_.Get();
    out->end_line = cursor_.line();
    if (in_comment_) {
      in_comment_ = !(c == '*' && cursor_.PeekNext() == '/');
      if (!in_comment_) cursor_.Advance();
      cursor_.Advance();
      if (c == '\n' && !directive_) return true;
    } else if (c == '\n') {
      cursor_.Advance();
      return true;
    } else if (c == ';' || (c == '/' && cursor_.PeekNext() == '/')) {
      while (!cursor_.AtEnd() && cursor_.Get() != '\n') cursor_.Advance();
    } else if (c == '/' && cursor_.PeekNext() == '*') {
      in_comment_ = true;
      comment_line_ = cursor_.line();
      comment_column_ = cursor_.column();
      Take(out, ' ');
      cursor_.Advance();
    } else if (c == '"' && directive_) {
      // Strings matter only in directives (#include "a;b.h"); elsewhere a quote is ordinary
      // text, so that an unbalanced one cannot hide a comment.
      Take(out, c);
      while (!cursor_.AtEnd() && cursor_.Get() != '\n' && cursor_.Get() != '"') Take(out, cursor_.Get());
      if (!cursor_.AtEnd() && cursor_.Get() == '"') Take(out, c);
    } else {
      Take(out, c);
    }
  }
  return true;
}

// The ids of the macros whose expansion produced a token, which never expand it again: this is
// what makes self-referential and mutually recursive macros terminate. Shared because all tokens
// of one expansion carry the same set. Sorted and unique; null means empty.
using HideSet = std::shared_ptr<const std::vector<int>>;

bool InHideSet(const HideSet& set, int id) { return set && std::binary_search(set->begin(), set->end(), id); }

HideSet HideSetUnion(const HideSet& a, const HideSet& b) {
  if (!a || a == b) return b;
  if (!b || std::includes(a->begin(), a->end(), b->begin(), b->end())) return a;
  if (std::includes(b->begin(), b->end(), a->begin(), a->end())) return b;
  auto merged = std::make_shared<std::vector<int>>();
  std::set_union(a->begin(), a->end(), b->begin(), b->end(), std::back_inserter(*merged));
  return merged;
}

HideSet HideSetIntersection(const HideSet& a, const HideSet& b) {
  if (!a || !b || a == b) return b ? a : nullptr;
  auto common = std::make_shared<std::vector<int>>();
  std::set_intersection(a->begin(), a->end(), b->begin(), b->end(), std::back_inserter(*common));
  return common->empty() ? nullptr : HideSet(std::move(common));
}

enum class TokenKind { kSpace, kIdentifier, kNumber, kString, kPunctuator };

struct Token {
  TokenKind kind = TokenKind::kPunctuator;
  std::string text;
  int column = 0;   // source column of the first character (of the macro name, for expansions)
  int offset = -1;  // index of the first character in the logical line; -1 for expansion output
  HideSet hide_set;
};

Token MakeToken(TokenKind kind, std::string text) {
  Token token;
  token.kind = kind;
  token.text = std::move(text);
  return token;
}

bool IsPunct(const Token& token, std::string_view text) {
  return token.kind == TokenKind::kPunctuator && token.text == text;
}

// Length of the token starting at s[i]. Numbers are pp-numbers, so "1e-3" or "0x1f" is one token
// and nothing inside it can be taken for a macro name.
std::size_t LexOne(std::string_view s, std::size_t i, TokenKind* kind) {
  auto at = [&](std::size_t k) { return k < s.size() ? s[k] : '\0'; };
  std::size_t j = i + 1;
  char c = s[i];
  if (IsSpace(c)) {
    *kind = TokenKind::kSpace;
    while (IsSpace(at(j))) ++j;
  } else if (IsIdentStart(c)) {
    *kind = TokenKind::kIdentifier;
    while (IsIdentChar(at(j))) ++j;
  } else if (IsDigit(c) || (c == '.' && IsDigit(at(i + 1)))) {
    *kind = TokenKind::kNumber;
    while (IsIdentChar(at(j)) || at(j) == '.') {
      bool exponent = std::string_view("eEpP").find(at(j)) != std::string_view::npos;
      j += exponent && (at(j + 1) == '+' || at(j + 1) == '-') ? 2 : 1;
    }
  } else if (c == '"') {
    *kind = TokenKind::kString;
    j = std::min(s.find('"', i + 1), s.size() - 1) + 1;
  } else {
    *kind = TokenKind::kPunctuator;
    for (std::string_view op : {"##", "<<", ">>", "<=", ">=", "==", "!=", "&&", "||"}) {
      if (s.substr(i, op.size()) == op) return op.size();
    }
  }
  return j - i;
}

std::vector<Token> Tokenize(std::string_view text, const std::vector<int>* columns) {
  std::vector<Token> tokens;
  for (std::size_t i = 0; i < text.size();) {
    Token token;
    std::size_t length = LexOne(text, i, &token.kind);
    token.text = text.substr(i, length);
    token.offset = static_cast<int>(i);
    token.column = columns != nullptr ? (*columns)[i] : 0;
    tokens.push_back(std::move(token));
    i += length;
  }
  return tokens;
}

std::size_t NextNonSpace(const std::vector<Token>& tokens, std::size_t i) {
  while (i < tokens.size() && tokens[i].kind == TokenKind::kSpace) ++i;
  return i;
}

int ColumnAt(const std::vector<Token>& tokens, std::size_t i, int fallback) {
  return i < tokens.size() ? tokens[i].column : fallback;
}

void TrimSpaces(std::vector<Token>* tokens) {
  while (!tokens->empty() && tokens->back().kind == TokenKind::kSpace) tokens->pop_back();
  tokens->erase(tokens->begin(), tokens->begin() + NextNonSpace(*tokens, 0));
}

// The ## operator: joins the last token of `out` with the first of `rhs` and appends the rest.
void Paste(std::vector<Token>* out, std::vector<Token> rhs) {
  std::size_t first = 0;
  if (!out->empty() && !rhs.empty()) {
    std::vector<Token> joined = Tokenize(out->back().text + rhs.front().text, nullptr);
    out->pop_back();
    for (Token& token : joined) out->push_back(MakeToken(token.kind, std::move(token.text)));
    first = 1;
  }
  out->insert(out->end(), rhs.begin() + first, rhs.end());
}

// Evaluates a #if expression (macros already expanded, `defined` already replaced, no spaces)
// in 64-bit arithmetic that wraps instead of invoking undefined behaviour.
class ExpressionParser {
 public:
  ExpressionParser(std::vector<Token> tokens, int end_column) : tokens_(std::move(tokens)), end_column_(end_column) {}

  std::optional<std::int64_t> Evaluate() {
    if (tokens_.empty()) Fail(end_column_, "#if with no expression");
    std::int64_t value = Ternary(true, 0);
    if (pos_ < tokens_.size()) Fail(tokens_[pos_].column, Unexpected(tokens_[pos_]));
    if (failed_) return std::nullopt;
    return value;
  }
  int error_column() const { return error_column_; }
  const std::string& error_message() const { return error_message_; }

 private:
  static std::string Unexpected(const Token& token) {
    return fmt::format("unexpected '{}' in #if expression", token.text);
  }
  int CurrentColumn() const { return ColumnAt(tokens_, pos_, end_column_); }
  bool Accept(std::string_view punct) {
    if (pos_ >= tokens_.size() || !IsPunct(tokens_[pos_], punct)) return false;
    ++pos_;
    return true;
  }
  // Keeps the first error only and ends the parse, so later ones are not follow-on noise.
  void Fail(int column, std::string message) {
    if (!failed_) {
      error_column_ = column;
      error_message_ = std::move(message);
    }
    failed_ = true;
    pos_ = tokens_.size();
  }
  bool TooDeep(int depth) {
    if (depth > kMaxExpressionDepth) Fail(CurrentColumn(), "#if expression nested too deeply");
    return depth > kMaxExpressionDepth;
  }

  // `live` is false in the unevaluated operand of && || ?:, where 1/0 is no error (as in C).
  std::int64_t Ternary(bool live, int depth) {
    if (TooDeep(depth)) return 0;
    std::int64_t condition = Binary(1, live, depth);
    if (!Accept("?")) return condition;
    std::int64_t if_true = Ternary(live && condition != 0, depth + 1);
    if (!Accept(":")) Fail(CurrentColumn(), "expected ':' in #if expression");
    std::int64_t if_false = Ternary(live && condition == 0, depth + 1);
    return condition != 0 ? if_true : if_false;
  }

  static int Precedence(const std::string& op) {
    static constexpr std::pair<std::string_view, int> kTable[] = {
        {"||", 1}, {"&&", 2}, {"|", 3},  {"^", 4},  {"&", 5}, {"==", 6}, {"!=", 6}, {"<", 7},  {">", 7},
        {"<=", 7}, {">=", 7}, {"<<", 8}, {">>", 8}, {"+", 9}, {"-", 9},  {"*", 10}, {"/", 10}, {"%", 10}};
    for (const auto& [text, precedence] : kTable) {
      if (op == text) return precedence;
    }
    return 0;
  }

  std::int64_t Binary(int min_precedence, bool live, int depth) {
    std::int64_t lhs = Unary(live, depth);
    while (pos_ < tokens_.size() && tokens_[pos_].kind == TokenKind::kPunctuator) {
      const Token& op = tokens_[pos_];
      int precedence = Precedence(op.text);
      if (precedence == 0 || precedence < min_precedence) break;
      ++pos_;
      bool rhs_live = live && !(op.text == "&&" && lhs == 0) && !(op.text == "||" && lhs != 0);
      lhs = Apply(op, lhs, Binary(precedence + 1, rhs_live, depth), rhs_live);
    }
    return lhs;
  }

  std::int64_t Apply(const Token& op, std::int64_t lhs, std::int64_t rhs, bool live) {
    const std::string& o = op.text;
    auto u = [](std::int64_t v) { return static_cast<std::uint64_t>(v); };
    auto s = [](std::uint64_t v) { return static_cast<std::int64_t>(v); };
    if (o == "||") return lhs != 0 || rhs != 0;
    if (o == "&&") return lhs != 0 && rhs != 0;
    if (o == "|") return lhs | rhs;
    if (o == "^") return lhs ^ rhs;
    if (o == "&") return lhs & rhs;
    if (o == "==") return lhs == rhs;
    if (o == "!=") return lhs != rhs;
    if (o == "<") return lhs < rhs;
    if (o == ">") return lhs > rhs;
    if (o == "<=") return lhs <= rhs;
    if (o == ">=") return lhs >= rhs;
    if (o == "<<") return rhs < 0 || rhs >= 64 ? 0 : s(u(lhs) << rhs);
    if (o == ">>") return rhs < 0 ? 0 : rhs >= 64 ? (lhs < 0 ? -1 : 0) : lhs >> rhs;
    if (o == "+") return s(u(lhs) + u(rhs));
    if (o == "-") return s(u(lhs) - u(rhs));
    if (o == "*") return s(u(lhs) * u(rhs));
    if (rhs == 0 && live) Fail(op.column, "division by zero in #if expression");
    if (rhs == 0) return 0;
    if (rhs == -1) return o == "/" ? s(0 - u(lhs)) : 0;  // INT64_MIN / -1 overflows
    return o == "/" ? lhs / rhs : lhs % rhs;
  }

  std::int64_t Unary(bool live, int depth) {
    if (TooDeep(depth)) return 0;
    if (pos_ >= tokens_.size()) Fail(end_column_, "unexpected end of #if expression");
    if (failed_) return 0;
    const Token& token = tokens_[pos_++];
    if (IsPunct(token, "(")) {
      std::int64_t value = Ternary(live, depth + 1);
      if (!Accept(")")) Fail(CurrentColumn(), "expected ')' in #if expression");
      return value;
    }
    // Negation through unsigned, so that -INT64_MIN wraps instead of trapping.
    if (IsPunct(token, "-")) return static_cast<std::int64_t>(0 - static_cast<std::uint64_t>(Unary(live, depth + 1)));
    if (IsPunct(token, "+")) return Unary(live, depth + 1);
    if (IsPunct(token, "!")) return Unary(live, depth + 1) == 0;
    if (IsPunct(token, "~")) return ~Unary(live, depth + 1);
    if (token.kind == TokenKind::kIdentifier) return 0;  // C: unknown names count as 0
    if (token.kind == TokenKind::kNumber) return ParseInteger(token);
    Fail(token.column, Unexpected(token));
    return 0;
  }

  // Decimal, 0x hex or 0 octal, with u/l suffixes ignored; "1.5" or "08" is an error, as in C.
  std::int64_t ParseInteger(const Token& token) {
    std::string_view digits = token.text;
    while (!digits.empty() && std::string_view("uUlL").find(digits.back()) != std::string_view::npos) {
      digits.remove_suffix(1);
    }
    bool hex = digits.size() > 1 && digits[0] == '0' && (digits[1] == 'x' || digits[1] == 'X');
    int base = hex ? 16 : digits.size() > 1 && digits[0] == '0' ? 8 : 10;
    digits.remove_prefix(hex ? 2 : base == 8 ? 1 : 0);
    std::uint64_t value = 0;
    auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value, base);
    bool valid = !digits.empty() && error == std::errc() && end == digits.data() + digits.size();
    if (!valid) Fail(token.column, fmt::format("invalid integer constant '{}' in #if expression", token.text));
    return valid ? static_cast<std::int64_t>(value) : 0;
  }

  std::vector<Token> tokens_;
  int end_column_;
  std::size_t pos_ = 0;
  bool failed_ = false;
  int error_column_ = 0;
  std::string error_message_;
};

struct Macro {
  int id = 0;    // the same for every definition of one name
  HideSet self;  // {id}, kept to avoid building it for each use
  bool function_like = false;
  std::vector<std::string> params;
  std::vector<Token> body;  // spaces inside collapsed to one, none at either end
};

class Preprocessor {
 public:
  Preprocessor(const PreprocessOptions& options, const FileReader& reader) : options_(options), reader_(reader) {
    std::size_t max = std::numeric_limits<std::size_t>::max();
    work_limit_ = options.max_output_bytes > max - kWorkSlack ? max : options.max_output_bytes + kWorkSlack;
  }
  PreprocessResult Run(std::string_view text, const std::string& file_name);

 private:
  struct Conditional {
    SourceLoc loc;
    std::string directive;  // if, ifdef or ifndef, for the unterminated message
    bool parent_active = true;
    bool taken = false;   // a branch has been chosen, so later #elif/#else are skipped
    bool active = false;  // lines of the current branch are kept
    bool seen_else = false;
  };
  struct FileState {
    std::filesystem::path path;  // where it was found: #include "..." looks beside it
    std::string name;            // reported name, which #line may change
    int line_offset = 0;         // added to physical line numbers by #line
    std::vector<Conditional> conditionals;
  };
  using Args = std::vector<std::vector<Token>>;

  SourceLoc Loc(int column) const { return {file_->name, ReportedLine(), column}; }
  int ReportedLine() const { return line_->line + file_->line_offset; }
  void Error(int column, DiagnosticCode code, std::string message) {
    result_.diagnostics.Error(Loc(column), code, std::move(message));
  }
  bool Active() const { return file_->conditionals.empty() || file_->conditionals.back().active; }
  bool IsDefined(const std::string& name) const { return macros_.count(name) != 0; }
  bool ChargeWork(std::size_t units, int column);
  const Token* ExpectName(const std::vector<Token>& rest, const char* directive, int column);

  void ProcessFile(std::string_view text, FileState* file, int depth);
  void ProcessLine(const LogicalLine& line, int depth);
  void EmitLine(const std::vector<Token>& tokens);
  void HandleDirective(const std::vector<Token>& tokens, std::size_t hash, int depth);
  void HandleConditional(const std::string& directive, int column, const std::vector<Token>& rest);
  bool EvaluateCondition(const std::vector<Token>& rest, int column);
  bool ReplaceDefined(const std::vector<Token>& rest, std::vector<Token>* out);
  void HandleDefine(const std::vector<Token>& rest, int column);
  bool ParseParameters(const std::vector<Token>& rest, std::size_t* i, int column, Macro* macro);
  void HandleInclude(const std::vector<Token>& rest, int column, int depth);
  void HandleLine(const std::vector<Token>& rest, int column);

  std::vector<Token> Expand(std::vector<Token> input, int depth);
  bool ReplaceMacro(const Macro& macro, const Token& name, std::vector<Token>* pending, int depth,
                    std::vector<Token>* out);
  bool CollectArguments(const Macro& macro, const Token& name, const std::vector<Token>& pending, Args* args,
                        std::size_t* rparen);
  bool CheckArgumentCount(const Macro& macro, const Token& name, Args* args);
  std::vector<Token> Substitute(const Macro& macro, const Args& args, int depth);

  const PreprocessOptions& options_;
  const FileReader& reader_;
  PreprocessResult result_;
  std::unordered_map<std::string, Macro> macros_;
  std::unordered_map<std::string, int> macro_ids_;  // hide sets hold small ids rather than names
  std::set<std::string> pragma_once_;               // lexically normal paths of #pragma once files
  FileState* file_ = nullptr;                       // the file and line being processed
  const LogicalLine* line_ = nullptr;
  std::size_t output_bytes_ = 0;
  std::size_t work_ = 0;  // expansion and inclusion work, bounded so nothing can run away
  std::size_t work_limit_ = 0;
  bool stopped_ = false;  // a limit was hit: the rest of the input is ignored
};

bool Preprocessor::ChargeWork(std::size_t units, int column) {
  work_ += units;
  if (work_ > work_limit_ && !stopped_) {
    Error(column, DiagnosticCode::kExpansionLimit,
          fmt::format("macro or #include expansion exceeds the output limit of {} bytes", options_.max_output_bytes));
    stopped_ = true;
  }
  return !stopped_;
}

const Token* Preprocessor::ExpectName(const std::vector<Token>& rest, const char* directive, int column) {
  std::size_t i = NextNonSpace(rest, 0);
  if (i < rest.size() && rest[i].kind == TokenKind::kIdentifier) return &rest[i];
  Error(ColumnAt(rest, i, column), DiagnosticCode::kMacroDefinition, fmt::format("#{} needs a macro name", directive));
  return nullptr;
}

PreprocessResult Preprocessor::Run(std::string_view text, const std::string& file_name) {
  // Command-line definitions go through the #define parser, so "F(x)" names work too.
  FileState command_line{"", "<command line>", 0, {}};
  LogicalLine no_line;
  file_ = &command_line;
  line_ = &no_line;
  for (const auto& [name, value] : options_.defines) HandleDefine(Tokenize(name + " " + value, nullptr), 0);
  FileState main_file{file_name, file_name, 0, {}};
  ProcessFile(text, &main_file, 0);
  return std::move(result_);
}

void Preprocessor::ProcessFile(std::string_view text, FileState* file, int depth) {
  LineSplitter splitter(text);
  LogicalLine line;
  while (!stopped_ && splitter.Next(&line)) {
    file_ = file;  // an #include on the previous line pointed these elsewhere
    line_ = &line;
    ProcessLine(line, depth);
  }
  if (stopped_) return;
  if (splitter.in_comment()) {
    result_.diagnostics.Error({file->name, splitter.comment_line() + file->line_offset, splitter.comment_column()},
                              DiagnosticCode::kUnterminatedComment, "unterminated /* comment");
  }
  for (const Conditional& conditional : file->conditionals) {
    result_.diagnostics.Error(conditional.loc, DiagnosticCode::kUnbalancedConditional,
                              fmt::format("unterminated #{}", conditional.directive));
  }
}

void Preprocessor::ProcessLine(const LogicalLine& line, int depth) {
  std::vector<Token> tokens = Tokenize(line.text, &line.columns);
  std::size_t first = NextNonSpace(tokens, 0);
  if (first < tokens.size() && tokens[first].kind == TokenKind::kPunctuator && tokens[first].text[0] == '#') {
    HandleDirective(tokens, first, depth);
  } else if (Active()) {
    EmitLine(Expand(std::move(tokens), 0));
  }
}

void Preprocessor::EmitLine(const std::vector<Token>& tokens) {
  if (stopped_) return;
  PreprocessedLine out{"", file_->name, ReportedLine(), {}};
  for (const Token& token : tokens) {
    out.text += token.text;
    for (std::size_t i = 0; i < token.text.size(); ++i) {
      out.columns.push_back(token.offset >= 0 ? line_->columns[token.offset + i] : token.column);
    }
  }
  std::size_t begin = 0, end = out.text.size();
  while (end > 0 && IsSpace(out.text[end - 1])) --end;
  while (begin < end && IsSpace(out.text[begin])) ++begin;
  if (begin == end) return;
  out.text = out.text.substr(begin, end - begin);
  out.columns = std::vector<int>(out.columns.begin() + begin, out.columns.begin() + end);
  output_bytes_ += out.text.size() + 1;
  if (output_bytes_ > options_.max_output_bytes) {
    Error(out.columns[0], DiagnosticCode::kExpansionLimit,
          fmt::format("preprocessed output exceeds the limit of {} bytes", options_.max_output_bytes));
    stopped_ = true;
    return;
  }
  result_.lines.push_back(std::move(out));
}

void Preprocessor::HandleDirective(const std::vector<Token>& tokens, std::size_t hash, int depth) {
  int column = tokens[hash].column;
  std::size_t name_index = NextNonSpace(tokens, hash + 1);
  if (tokens[hash].text != "#") {
    if (Active()) Error(column, DiagnosticCode::kUnknownDirective,
                        fmt::format("invalid directive '{}'", tokens[hash].text));
    return;
  }
  if (name_index == tokens.size()) return;  // a lone '#' is the null directive
  const Token& name = tokens[name_index];
  const std::vector<Token> rest(tokens.begin() + name_index + 1, tokens.end());
  const std::string directive = name.kind == TokenKind::kIdentifier ? name.text : "";
  if (directive == "if" || directive == "ifdef" || directive == "ifndef" || directive == "elif" ||
      directive == "else" || directive == "endif") {
    HandleConditional(directive, column, rest);
  } else if (!Active()) {
    return;  // skipped text may hold anything, even unknown directives
  } else if (directive == "define") {
    HandleDefine(rest, column);
  } else if (directive == "undef") {
    if (const Token* macro = ExpectName(rest, "undef", column)) macros_.erase(macro->text);
  } else if (directive == "include") {
    HandleInclude(rest, column, depth);
  } else if (directive == "line") {
    HandleLine(rest, column);
  } else if (directive == "error" || directive == "warning") {
    std::vector<Token> words = rest;
    TrimSpaces(&words);
    std::string message = "#" + directive + (words.empty() ? "" : " ");
    for (const Token& token : words) message += token.text;
    if (directive == "error") Error(column, DiagnosticCode::kErrorDirective, message);
    if (directive == "warning") result_.diagnostics.Warning(Loc(column), DiagnosticCode::kWarningDirective, message);
  } else if (directive == "pragma") {
    std::size_t i = NextNonSpace(rest, 0);
    if (i < rest.size() && rest[i].text == "once") pragma_once_.insert(file_->path.lexically_normal().string());
  } else {
    Error(name.column, DiagnosticCode::kUnknownDirective, fmt::format("unknown directive '#{}'", name.text));
  }
}

void Preprocessor::HandleConditional(const std::string& directive, int column, const std::vector<Token>& rest) {
  std::vector<Conditional>& stack = file_->conditionals;
  if (directive == "if" || directive == "ifdef" || directive == "ifndef") {
    bool parent_active = Active();
    bool value = false;
    if (parent_active && directive == "if") {
      value = EvaluateCondition(rest, column);
    } else if (parent_active) {
      const Token* name = ExpectName(rest, directive.c_str(), column);
      value = name != nullptr && IsDefined(name->text) == (directive == "ifdef");
    }
    stack.push_back({Loc(column), directive, parent_active, value, value, false});
    return;
  }
  if (stack.empty()) {
    Error(column, DiagnosticCode::kUnbalancedConditional, fmt::format("#{} without #if", directive));
    return;
  }
  Conditional& top = stack.back();
  if (directive == "endif") {
    stack.pop_back();
  } else if (top.seen_else) {
    Error(column, DiagnosticCode::kUnbalancedConditional, fmt::format("#{} after #else", directive));
    top.active = false;
  } else if (directive == "else") {
    top.seen_else = true;
    top.active = top.parent_active && !top.taken;
    top.taken = true;
  } else {  // #elif is evaluated only when no earlier branch was taken
    top.active = top.parent_active && !top.taken && EvaluateCondition(rest, column);
    top.taken = top.taken || top.active;
  }
}

bool Preprocessor::EvaluateCondition(const std::vector<Token>& rest, int column) {
  std::vector<Token> replaced;
  if (!ReplaceDefined(rest, &replaced)) return false;
  std::vector<Token> significant;
  for (Token& token : Expand(std::move(replaced), 0)) {
    if (token.kind != TokenKind::kSpace) significant.push_back(std::move(token));
  }
  ExpressionParser parser(std::move(significant), column);
  std::optional<std::int64_t> value = parser.Evaluate();
  if (!value) Error(parser.error_column(), DiagnosticCode::kConditionExpression, parser.error_message());
  return value.value_or(0) != 0;
}

// `defined X` must be answered before expansion, or X would be replaced by its body.
bool Preprocessor::ReplaceDefined(const std::vector<Token>& rest, std::vector<Token>* out) {
  for (std::size_t i = 0; i < rest.size(); ++i) {
    out->push_back(rest[i]);
    if (rest[i].kind != TokenKind::kIdentifier || rest[i].text != "defined") continue;
    std::size_t j = NextNonSpace(rest, i + 1);
    bool parenthesised = j < rest.size() && IsPunct(rest[j], "(");
    if (parenthesised) j = NextNonSpace(rest, j + 1);
    std::size_t end = parenthesised ? NextNonSpace(rest, j + 1) : j;
    if (j >= rest.size() || rest[j].kind != TokenKind::kIdentifier ||
        (parenthesised && (end >= rest.size() || !IsPunct(rest[end], ")")))) {
      Error(rest[i].column, DiagnosticCode::kConditionExpression, "'defined' needs a macro name, or (name)");
      return false;
    }
    out->back().kind = TokenKind::kNumber;
    out->back().text = IsDefined(rest[j].text) ? "1" : "0";
    i = end;
  }
  return true;
}

void Preprocessor::HandleDefine(const std::vector<Token>& rest, int column) {
  const Token* name = ExpectName(rest, "define", column);
  if (name == nullptr) return;
  if (name->text == "defined") {
    Error(name->column, DiagnosticCode::kMacroDefinition, "'defined' cannot be used as a macro name");
    return;
  }
  Macro macro;
  macro.id = macro_ids_.emplace(name->text, static_cast<int>(macro_ids_.size())).first->second;
  macro.self = std::make_shared<const std::vector<int>>(1, macro.id);
  std::size_t i = static_cast<std::size_t>(name - rest.data()) + 1;
  // Only a '(' touching the name makes a function-like macro: "#define N (1)" is object-like.
  if (i < rest.size() && IsPunct(rest[i], "(")) {
    macro.function_like = true;
    if (!ParseParameters(rest, &i, column, &macro)) return;
  }
  std::vector<Token> body(rest.begin() + i, rest.end());
  TrimSpaces(&body);
  for (Token& token : body) {
    token.offset = -1;
    if (token.kind != TokenKind::kSpace) {
      macro.body.push_back(std::move(token));
    } else if (macro.body.back().kind != TokenKind::kSpace) {  // trimmed: never first
      macro.body.push_back(MakeToken(TokenKind::kSpace, " "));
    }
  }
  if (!macro.body.empty() && (IsPunct(macro.body.front(), "##") || IsPunct(macro.body.back(), "##"))) {
    Error(name->column, DiagnosticCode::kMacroDefinition, "'##' cannot appear at either end of a macro body");
    return;
  }
  macros_[name->text] = std::move(macro);
}

// Parses "(a, b)" starting at the '(' at *i; leaves *i after the ')'.
bool Preprocessor::ParseParameters(const std::vector<Token>& rest, std::size_t* i, int column, Macro* macro) {
  std::size_t j = NextNonSpace(rest, *i + 1);
  bool more = j >= rest.size() || !IsPunct(rest[j], ")");
  while (more) {
    std::vector<std::string>& params = macro->params;
    if (j >= rest.size() || rest[j].kind != TokenKind::kIdentifier) {
      Error(ColumnAt(rest, j, column), DiagnosticCode::kMacroDefinition, "expected a parameter name in #define");
      return false;
    } else if (std::find(params.begin(), params.end(), rest[j].text) != params.end()) {
      Error(rest[j].column, DiagnosticCode::kMacroDefinition,
            fmt::format("duplicate macro parameter '{}'", rest[j].text));
      return false;
    } else {
      params.push_back(rest[j].text);
    }
    j = NextNonSpace(rest, j + 1);
    more = j < rest.size() && IsPunct(rest[j], ",");
    if (!more && (j >= rest.size() || !IsPunct(rest[j], ")"))) {
      Error(ColumnAt(rest, j, column), DiagnosticCode::kMacroDefinition, "expected ',' or ')' in macro parameter list");
      return false;
    }
    if (more) j = NextNonSpace(rest, j + 1);
  }
  *i = j + 1;
  return true;
}

// Reads "file" or <file>; `quoted` tells which, since only "file" looks beside the includer.
bool ParseIncludeName(const std::vector<Token>& tokens, std::string* name, bool* quoted) {
  std::size_t i = NextNonSpace(tokens, 0);
  if (i == tokens.size()) return false;
  const std::string& text = tokens[i].text;
  *quoted = tokens[i].kind == TokenKind::kString;
  if (*quoted) {
    *name = text.size() >= 2 && text.back() == '"' ? text.substr(1, text.size() - 2) : "";
    return !name->empty();
  }
  if (!IsPunct(tokens[i], "<")) return false;
  name->clear();
  for (++i; i < tokens.size() && !IsPunct(tokens[i], ">"); ++i) *name += tokens[i].text;
  return i < tokens.size() && !name->empty();
}

void Preprocessor::HandleInclude(const std::vector<Token>& rest, int column, int depth) {
  std::string name;
  bool quoted = false;
  if (!ParseIncludeName(rest, &name, &quoted) && !ParseIncludeName(Expand(rest, 0), &name, &quoted)) {
    Error(column, DiagnosticCode::kMalformedDirective, "#include expects \"file\" or <file>");
    return;
  }
  int max_depth = std::min(options_.max_include_depth, kMaxIncludeDepthCap);
  if (depth + 1 > max_depth) {
    // Nearly always a cycle; going on would repeat the same error at every level.
    Error(column, DiagnosticCode::kIncludeTooDeep,
          fmt::format("#include nested more than {} levels deep (include cycle?)", max_depth));
    stopped_ = true;
    return;
  }
  std::replace(name.begin(), name.end(), '\\', '/');  // DX8 shaders were written on Windows
  std::vector<std::filesystem::path> candidates;
  if (quoted) candidates.push_back(file_->path.parent_path() / name);
  for (const std::filesystem::path& dir : options_.include_dirs) candidates.push_back(dir / name);
  std::string reader_failure;  // why the caller's reader threw, for the error below
  for (const std::filesystem::path& candidate : candidates) {
    std::optional<std::string> text;
    try {  // the reader is the caller's code; a throwing one must not unwind through us
      if (reader_) text = reader_(candidate);
    } catch (const std::exception& e) {
      if (reader_failure.empty()) reader_failure = fmt::format(" ({}: {})", candidate.string(), e.what());
    } catch (...) {
      if (reader_failure.empty()) reader_failure = fmt::format(" ({}: the reader failed)", candidate.string());
    }
    if (!text) continue;
    if (pragma_once_.count(candidate.lexically_normal().string()) != 0) return;
    if (!ChargeWork(text->size() + 64, column)) return;
    FileState included{candidate, candidate.string(), 0, {}};
    FileState* includer = file_;
    const LogicalLine* include_line = line_;
    ProcessFile(*text, &included, depth + 1);
    file_ = includer;
    line_ = include_line;
    return;
  }
  Error(column, DiagnosticCode::kIncludeNotFound, fmt::format("cannot open include file '{}'{}", name, reader_failure));
}

void Preprocessor::HandleLine(const std::vector<Token>& rest, int column) {
  std::vector<Token> tokens = Expand(rest, 0);
  std::size_t i = NextNonSpace(tokens, 0);
  std::string number = i < tokens.size() ? tokens[i].text : "";
  bool valid = !number.empty() && number.size() <= 9 && std::all_of(number.begin(), number.end(), IsDigit);
  if (!valid || std::stoi(number) == 0) {
    Error(ColumnAt(tokens, i, column), DiagnosticCode::kMalformedDirective,
          "#line needs a line number from 1 to 999999999");
    return;
  }
  std::size_t j = NextNonSpace(tokens, i + 1);
  if (j < tokens.size()) {
    const std::string& text = tokens[j].text;
    if (tokens[j].kind != TokenKind::kString || text.size() < 2 || text.back() != '"') {
      Error(tokens[j].column, DiagnosticCode::kMalformedDirective, "#line expects a file name in double quotes");
      return;
    }
    file_->name = text.substr(1, text.size() - 2);
  }
  file_->line_offset = std::stoi(number) - (line_->end_line + 1);
}

// Prosser's algorithm: replacements are pushed back onto the input, so a function-like macro
// name produced by one expansion can take its arguments from the text that follows, and hide
// sets stop recursion. `pending` holds the rest of the input reversed (next token at the back).
std::vector<Token> Preprocessor::Expand(std::vector<Token> input, int depth) {
  if (depth > kMaxExpansionDepth) {
    Error(ColumnAt(input, 0, 0), DiagnosticCode::kExpansionLimit, "macro arguments nested too deeply");
    return input;
  }
  std::vector<Token> output;
  std::vector<Token> pending(std::make_move_iterator(input.rbegin()), std::make_move_iterator(input.rend()));
  while (!pending.empty() && !stopped_) {
    Token token = std::move(pending.back());
    pending.pop_back();
    auto macro = token.kind == TokenKind::kIdentifier ? macros_.find(token.text) : macros_.end();
    std::vector<Token> replacement;
    if (macro == macros_.end() || InHideSet(token.hide_set, macro->second.id) ||
        !ReplaceMacro(macro->second, token, &pending, depth, &replacement)) {
      output.push_back(std::move(token));
      continue;
    }
    std::size_t units = kTokenWork;
    for (const Token& piece : replacement) units += piece.text.size() + kTokenWork;
    if (!ChargeWork(units, token.column)) break;
    pending.insert(pending.end(), std::make_move_iterator(replacement.rbegin()),
                   std::make_move_iterator(replacement.rend()));
  }
  return output;
}

// Builds the replacement for one use of `macro`, taking a function-like macro's arguments off
// `pending`. False when `name` is not a use (no argument list follows) or the call is bad.
bool Preprocessor::ReplaceMacro(const Macro& macro, const Token& name, std::vector<Token>* pending, int depth,
                                std::vector<Token>* out) {
  HideSet hide_set = name.hide_set;
  Args args;
  if (macro.function_like) {
    std::size_t rparen = 0;
    if (!CollectArguments(macro, name, *pending, &args, &rparen)) return false;
    hide_set = HideSetIntersection(hide_set, (*pending)[rparen].hide_set);
    pending->resize(rparen);
  }
  hide_set = HideSetUnion(hide_set, macro.self);
  *out = Substitute(macro, args, depth);
  for (Token& token : *out) {
    token.hide_set = HideSetUnion(token.hide_set, hide_set);
    token.column = name.column;
    token.offset = -1;
  }
  return true;
}

bool Preprocessor::CollectArguments(const Macro& macro, const Token& name, const std::vector<Token>& pending,
                                    Args* args, std::size_t* rparen) {
  std::size_t i = pending.size();
  while (i > 0 && pending[i - 1].kind == TokenKind::kSpace) --i;
  if (i == 0 || !IsPunct(pending[i - 1], "(")) return false;
  const std::size_t start = --i;
  // Find the closing parenthesis before copying anything: on a line with many unterminated
  // calls, each one scans to the end. The scan is charged as work, which bounds that.
  for (int nesting = 0; i > 0 && (nesting > 0 || !IsPunct(pending[i - 1], ")")); --i) {
    nesting += IsPunct(pending[i - 1], "(") ? 1 : IsPunct(pending[i - 1], ")") ? -1 : 0;
  }
  if (!ChargeWork(start - i + 1, name.column)) return false;
  if (i == 0) {
    Error(name.column, DiagnosticCode::kMacroInvocation,
          fmt::format("unterminated argument list invoking macro '{}'", name.text));
    return false;
  }
  *rparen = i - 1;
  args->emplace_back();
  int nesting = 0;
  for (std::size_t k = start; k-- > i;) {
    const Token& token = pending[k];
    nesting += IsPunct(token, "(") ? 1 : IsPunct(token, ")") ? -1 : 0;
    if (nesting == 0 && IsPunct(token, ",")) {
      args->emplace_back();
    } else {
      args->back().push_back(token);
    }
  }
  return CheckArgumentCount(macro, name, args);
}

bool Preprocessor::CheckArgumentCount(const Macro& macro, const Token& name, Args* args) {
  for (std::vector<Token>& arg : *args) TrimSpaces(&arg);
  std::size_t expected = macro.params.size();
  if (expected == 0 && args->size() == 1 && args->front().empty()) args->clear();
  if (args->size() == expected) return true;
  Error(name.column, DiagnosticCode::kMacroInvocation,
        fmt::format("macro '{}' expects {} argument{}, got {}", name.text, expected,
                                 expected == 1 ? "" : "s", args->size()));
  return false;
}

std::vector<Token> Preprocessor::Substitute(const Macro& macro, const Args& args, int depth) {
  const std::vector<Token>& body = macro.body;
  auto param_index = [&](std::size_t i) -> int {
    if (i >= body.size() || body[i].kind != TokenKind::kIdentifier) return -1;
    auto it = std::find(macro.params.begin(), macro.params.end(), body[i].text);
    return it == macro.params.end() ? -1 : static_cast<int>(it - macro.params.begin());
  };
  std::vector<std::optional<std::vector<Token>>> expanded(args.size());
  std::vector<Token> out;
  for (std::size_t i = 0; i < body.size(); ++i) {
    std::size_t next = NextNonSpace(body, i + 1);
    int param = param_index(i);
    if (IsPunct(body[i], "##") && next < body.size()) {
      while (!out.empty() && out.back().kind == TokenKind::kSpace) out.pop_back();
      Paste(&out, param_index(next) >= 0 ? args[param_index(next)] : std::vector<Token>{body[next]});
      i = next;
    } else if (param >= 0 && next < body.size() && IsPunct(body[next], "##")) {
      out.insert(out.end(), args[param].begin(), args[param].end());  // ## pastes arguments as written
    } else if (param >= 0) {
      // Other arguments are fully expanded before substitution, as in C.
      if (!expanded[param]) expanded[param] = Expand(args[param], depth + 1);
      out.insert(out.end(), expanded[param]->begin(), expanded[param]->end());
    } else {
      out.push_back(body[i]);
    }
  }
  return out;
}

}  // namespace

std::optional<std::string> ReadFileFromDisk(const std::filesystem::path& path) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) return std::nullopt;
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) return std::nullopt;
  return text;
}

PreprocessResult Preprocess(std::string_view text, const std::string& file_name, const PreprocessOptions& options,
                            const FileReader& reader) {
  // Only std::bad_alloc can get here (every input problem is a diagnostic); it must not escape.
  try {
    Preprocessor preprocessor(options, reader);
    return preprocessor.Run(text, file_name);
  } catch (const std::exception& e) {
    PreprocessResult result;
    result.diagnostics.Error({file_name, 0, 0}, DiagnosticCode::kPreprocessorFailure,
                             fmt::format("preprocessing failed: {}", e.what()));
    return result;
  }
}

}  // namespace vs11
