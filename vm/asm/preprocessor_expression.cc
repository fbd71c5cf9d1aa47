// See vm/asm/preprocessor_expression.h.
#include "vm/asm/preprocessor_expression.h"

#include <fmt/format.h>

#include <charconv>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

namespace vs11::preprocessing {
namespace {

// Hostile input must not exhaust the stack: parentheses, unary operators and ?: nest at most this deep.
constexpr int kMaxExpressionDepth = 256;

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

}  // namespace

Result<std::int64_t> EvaluateExpression(std::vector<Token> tokens, int end_column) {
  ExpressionParser parser(std::move(tokens), end_column);
  const std::optional<std::int64_t> value = parser.Evaluate();
  if (value) return *value;
  return Failure(DiagnosticCode::kConditionExpression, parser.error_message(), SourceLoc{"", 0, parser.error_column()});
}

}  // namespace vs11::preprocessing
