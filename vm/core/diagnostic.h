// Problems found in user input (source text, bytecode, files), collected rather than thrown so that
// one pass can report many of them. Programmer errors use assert instead.
#pragma once

#include <string>
#include <vector>

namespace vs11 {

struct SourceLoc {
  std::string file;  // as the user named it; empty for bytecode without a source map
  int line = 0;      // 1-based; 0 = unknown
  int column = 0;    // 1-based; 0 = unknown
  friend bool operator==(const SourceLoc&, const SourceLoc&) = default;
};

enum class Severity { kError, kWarning, kNote };

struct Diagnostic {
  SourceLoc loc;
  Severity severity = Severity::kError;
  std::string message;
  // For bytecode problems: the index of the 32-bit word at fault, or -1.
  long word_offset = -1;
};

// "FILE:LINE:COL: error: MESSAGE" (parts that are unknown are left out).
std::string FormatDiagnostic(const Diagnostic& diagnostic);

class Diagnostics {
 public:
  // After this many errors, further errors are counted but not kept (a runaway file stays bounded).
  static constexpr int kMaxKeptErrors = 50;

  void Error(SourceLoc loc, std::string message);
  void Warning(SourceLoc loc, std::string message);
  void Add(Diagnostic diagnostic);
  void Append(const Diagnostics& other);

  bool HasErrors() const { return error_count_ > 0; }
  int error_count() const { return error_count_; }
  const std::vector<Diagnostic>& all() const { return items_; }
  // Every kept diagnostic, one formatted line each, plus a line for errors that were not kept.
  std::string ToString() const;

 private:
  std::vector<Diagnostic> items_;
  int error_count_ = 0;
};

}  // namespace vs11
