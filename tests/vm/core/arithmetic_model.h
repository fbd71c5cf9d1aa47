// An independent model of what each vs_1_1 instruction computes, written from the spec
// (../shared/spec/vs_1_1.md §3.1 and §3.3) and NOT from vm/core/semantics.h, which the engines share and
// which this model must not include: the differential tests compare the engines with each other, this
// model checks the formulas themselves. Values are computed in double and rounded to float
// explicitly after every operation the spec defines as an IEEE single-precision operation (for +, -,
// *, / and sqrt on floats, double then float rounds exactly as a float operation would: 53 >= 2 x 24
// + 2 bits). Where the spec gives only a precision (rcp, rsq, exp, log, lit's power, the partial
// precision lanes of expp and logp), the model gives the true value and the spec's bound.
#pragma once

#include <array>
#include <optional>
#include <string>

#include "vm/core/isa.h"

namespace vs11::model {

using Vec4 = std::array<float, 4>;

// What one result lane must be.
struct Expected {
  enum class Kind {
    kBits,         // exactly these bits (a value selected or built bit by bit: NaNs keep theirs)
    kValue,        // exactly this value, rounded once to float; any NaN for a NaN
    kWithin,       // within `relative` x |exact| + `absolute` of `exact` (an infinity: exactly it)
    kUnspecified,  // the spec leaves it open (see `rule`); anything is accepted
    kUnwritten,    // the instruction does not write this lane
  };
  Kind kind = Kind::kUnwritten;
  float value = 0.0f;           // kBits, kValue
  double exact = 0.0;           // kWithin
  double relative = 0.0;        // kWithin
  double absolute = 0.0;        // kWithin
  bool low_byte_clear = false;  // kWithin: the spec's reference clears the 8 low mantissa bits (expp.z, logp.z)
  const char* rule = "";        // the spec's words this lane follows, for messages
};

using Result = std::array<Expected, 4>;

// The registers an instruction under test reads: s0 = v[0], s1 = v[1], s2 = v[2]; a matrix
// instruction's s1 rows are v[1], v[2], v[3], v[4]. Sources carry no swizzle or negation (those are
// operand fetches, not arithmetic, and the differential tests cover them).
using Operands = std::array<Vec4, 5>;

// The expected result of `opcode` on `operands`; nullopt for opcodes without arithmetic (nop, dcl, def).
std::optional<Result> Model(Opcode opcode, const Operands& operands);

// Whether `actual` is what `expected` allows; if not, `why` says how it differs.
bool Accepts(const Expected& expected, float actual, std::string& why);

// For kWithin lanes: |actual - exact| as a fraction of the allowed error (0 = exact, 1 = at the bound).
double ErrorFraction(const Expected& expected, float actual);

}  // namespace vs11::model
