// The preprocessor's #if and #elif expressions (vm/asm/preprocessor.h), evaluated in 64-bit arithmetic
// that wraps instead of invoking undefined behaviour, with C's operators and precedence.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "vm/asm/preprocessor_tokens.h"

namespace vs11::preprocessing {

struct ExpressionResult {
  std::optional<std::int64_t> value;  // empty when the expression is bad
  int error_column = 0;               // of the first problem
  std::string error_message;
};

// `tokens`: the expression with macros already expanded, `defined` already replaced and no spaces;
// `end_column` is reported for problems at its end.
ExpressionResult EvaluateExpression(std::vector<Token> tokens, int end_column);

}  // namespace vs11::preprocessing
