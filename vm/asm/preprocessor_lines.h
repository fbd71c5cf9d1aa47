// The preprocessor's first pass (vm/asm/preprocessor.h): a file's text as logical lines, line splices
// joined and comments replaced by a space, with the source column of every character kept.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace vs11::preprocessing {

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
  void Take(LogicalLine* out, char c);

  Cursor cursor_;
  bool in_comment_ = false;
  int comment_line_ = 0;
  int comment_column_ = 0;
  bool blank_ = true;
  bool directive_ = false;
};

}  // namespace vs11::preprocessing
