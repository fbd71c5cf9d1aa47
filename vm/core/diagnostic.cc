#include "vm/core/diagnostic.h"

#include <fmt/format.h>

namespace vs11 {

std::string_view DiagnosticCodeName(DiagnosticCode code) {
  switch (code) {
#define VS11_DIAGNOSTIC_NAME(code, name) \
  case DiagnosticCode::code:             \
    return name;
    VS11_DIAGNOSTIC_CODES(VS11_DIAGNOSTIC_NAME)
#undef VS11_DIAGNOSTIC_NAME
  }
  return "unclassified";
}

std::string FormatDiagnostic(const Diagnostic& diagnostic) {
  std::string where;
  const SourceLoc& loc = diagnostic.loc;
  if (!loc.file.empty()) where += loc.file;
  if (loc.line > 0) where += fmt::format("{}{}", where.empty() ? "line " : ":", loc.line);
  if (loc.line > 0 && loc.column > 0) where += fmt::format(":{}", loc.column);
  if (diagnostic.word_offset >= 0) {
    where += fmt::format("{}word {}", where.empty() ? "" : ": ", diagnostic.word_offset);
  }
  const std::string_view kind = kSeverityNames.Name(diagnostic.severity);
  const std::string code = diagnostic.code == DiagnosticCode::kUnclassified
                               ? std::string()
                               : fmt::format(" [{}]", DiagnosticCodeName(diagnostic.code));
  return where.empty() ? fmt::format("{}: {}{}", kind, diagnostic.message, code)
                       : fmt::format("{}: {}: {}{}", where, kind, diagnostic.message, code);
}

void Diagnostics::Error(SourceLoc loc, DiagnosticCode code, std::string message) {
  Add({std::move(loc), Severity::kError, code, std::move(message)});
}

void Diagnostics::Warning(SourceLoc loc, DiagnosticCode code, std::string message) {
  Add({std::move(loc), Severity::kWarning, code, std::move(message)});
}

void Diagnostics::Add(Diagnostic diagnostic) {
  if (diagnostic.severity == Severity::kError) {
    ++error_count_;
    if (error_count_ > kMaxKeptErrors) return;
  } else if (items_.size() >= 4 * kMaxKeptErrors) {
    return;
  }
  items_.push_back(std::move(diagnostic));
}

void Diagnostics::Append(const Diagnostics& other) {
  for (const Diagnostic& d : other.items_) Add(d);
  // Errors the other list counted but did not keep still count here.
  int dropped = other.error_count_ - std::min(other.error_count_, kMaxKeptErrors);
  error_count_ += dropped;
}

std::string Diagnostics::ToString() const {
  std::string out;
  for (const Diagnostic& d : items_) out += FormatDiagnostic(d) + "\n";
  if (error_count_ > kMaxKeptErrors) {
    out += fmt::format("error: {} more errors not shown\n", error_count_ - kMaxKeptErrors);
  }
  return out;
}

}  // namespace vs11
