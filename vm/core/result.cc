#include "vm/core/result.h"

#include <cstdio>
#include <cstdlib>

namespace vs11 {

Diagnostic Failure(DiagnosticCode code, std::string message, SourceLoc loc) {
  return Diagnostic{.loc = std::move(loc), .severity = Severity::kError, .code = code, .message = std::move(message)};
}

namespace result_detail {

void ValueOfFailedResult(const Diagnostic& error) {
  std::fprintf(stderr, "vs11: the value of a failed Result was read: %s\n", FormatDiagnostic(error).c_str());
  std::abort();
}

void ErrorOfSuccessfulResult() {
  std::fputs("vs11: the error of a successful Result was read\n", stderr);
  std::abort();
}

}  // namespace result_detail
}  // namespace vs11
