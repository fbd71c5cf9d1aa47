// The preprocessor's tokens (vm/asm/preprocessor.h): pp-tokens of a logical line with their source
// columns, the hide sets that stop recursive macro expansion, and the ## operator's paste.
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace vs11::preprocessing {

constexpr bool IsSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }
constexpr bool IsDigit(char c) { return c >= '0' && c <= '9'; }
constexpr bool IsIdentStart(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; }
constexpr bool IsIdentChar(char c) { return IsIdentStart(c) || IsDigit(c); }

// The ids of the macros whose expansion produced a token, which never expand it again: this is
// what makes self-referential and mutually recursive macros terminate. Shared because all tokens
// of one expansion carry the same set. Sorted and unique; null means empty.
using HideSet = std::shared_ptr<const std::vector<int>>;

bool InHideSet(const HideSet& set, int id);
HideSet HideSetUnion(const HideSet& a, const HideSet& b);
HideSet HideSetIntersection(const HideSet& a, const HideSet& b);

enum class TokenKind { kSpace, kIdentifier, kNumber, kString, kPunctuator };

struct Token {
  TokenKind kind = TokenKind::kPunctuator;
  std::string text;
  int column = 0;   // source column of the first character (of the macro name, for expansions)
  int offset = -1;  // index of the first character in the logical line; -1 for expansion output
  HideSet hide_set;
};

Token MakeToken(TokenKind kind, std::string text);
bool IsPunct(const Token& token, std::string_view text);

// The tokens of `text`, with columns[i] the source column of text[i] (null: columns 0). Numbers are
// pp-numbers, so "1e-3" or "0x1f" is one token and nothing inside it can be taken for a macro name.
std::vector<Token> Tokenize(std::string_view text, const std::vector<int>* columns);

// The index of the first token at or after i that is not a space (tokens.size() if none).
std::size_t NextNonSpace(const std::vector<Token>& tokens, std::size_t i);
// The column of tokens[i], or `fallback` past the end.
int ColumnAt(const std::vector<Token>& tokens, std::size_t i, int fallback);
void TrimSpaces(std::vector<Token>* tokens);

// The ## operator: joins the last token of `out` with the first of `rhs` and appends the rest.
void Paste(std::vector<Token>* out, std::vector<Token> rhs);

}  // namespace vs11::preprocessing
