// The preprocessor's #if and #elif expressions (vm/asm/preprocessor.h), evaluated in 64-bit arithmetic
// that wraps instead of invoking undefined behaviour, with C's operators and precedence.
#pragma once

#include <cstdint>
#include <vector>

#include "vm/asm/preprocessor_tokens.h"
#include "vm/core/result.h"

namespace vs11::preprocessing {

// `tokens`: the expression with macros already expanded, `defined` already replaced and no spaces;
// `end_column` is reported for problems at its end. The value, or the first problem
// (kConditionExpression) with its column in the error's loc (the caller knows the file and line).
Result<std::int64_t> EvaluateExpression(std::vector<Token> tokens, int end_column);

}  // namespace vs11::preprocessing
