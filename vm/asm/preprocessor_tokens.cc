// See vm/asm/preprocessor_tokens.h.
#include "vm/asm/preprocessor_tokens.h"

#include <algorithm>
#include <iterator>
#include <utility>

namespace vs11::preprocessing {
namespace {

// Length of the token starting at s[i].
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

}  // namespace

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

Token MakeToken(TokenKind kind, std::string text) {
  Token token;
  token.kind = kind;
  token.text = std::move(text);
  return token;
}

bool IsPunct(const Token& token, std::string_view text) {
  return token.kind == TokenKind::kPunctuator && token.text == text;
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

}  // namespace vs11::preprocessing
