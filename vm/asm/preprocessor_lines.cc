// See vm/asm/preprocessor_lines.h.
#include "vm/asm/preprocessor_lines.h"

#include "vm/asm/preprocessor_tokens.h"

namespace vs11::preprocessing {

void LineSplitter::Take(LogicalLine* out, char c) {
  if (blank_ && !IsSpace(c)) {
    blank_ = false;
    directive_ = c == '#';
  }
  out->text.push_back(c);
  out->columns.push_back(cursor_.column());
  cursor_.Advance();
}

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

}  // namespace vs11::preprocessing
