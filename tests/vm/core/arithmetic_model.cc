#include "tests/vm/core/arithmetic_model.h"

#include <algorithm>
#include <bit>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>

namespace vs11::model {
namespace {

using Kind = Expected::Kind;

// One rounding to IEEE single precision (round to nearest even) of a value computed in double.
float Round(double x) { return static_cast<float>(x); }

double TwoTo(int exponent) { return std::ldexp(1.0, exponent); }

// The smallest denormal float: the absolute allowance for approximate results that underflow.
const double kDenormalStep = TwoTo(-149);

Expected Bits(float value, const char* rule) {
  Expected e;
  e.kind = Kind::kBits;
  e.value = value;
  e.rule = rule;
  return e;
}

Expected Value(double value, const char* rule) {
  Expected e;
  e.kind = Kind::kValue;
  e.value = Round(value);
  e.rule = rule;
  return e;
}

Expected Within(double exact, double relative, double absolute, const char* rule, bool low_byte_clear = false) {
  Expected e;
  e.kind = Kind::kWithin;
  e.exact = exact;
  e.relative = relative;
  e.absolute = absolute;
  e.low_byte_clear = low_byte_clear;
  e.rule = rule;
  return e;
}

Expected Unspecified(const char* rule) {
  Expected e;
  e.kind = Kind::kUnspecified;
  e.rule = rule;
  return e;
}

Result Replicated(const Expected& e) { return {e, e, e, e}; }

// IEEE single-precision operations on floats, each rounded once.
float Add(float a, float b) { return Round(static_cast<double>(a) + b); }
float Mul(float a, float b) { return Round(static_cast<double>(a) * b); }

// §3.3 dp3/dp4 and the matrix rows: a.x*b.x + a.y*b.y + ..., left to right as written, every product
// and every sum a float operation.
float Dot(const Vec4& a, const Vec4& b, int width) {
  float sum = Mul(a[0], b[0]);
  for (int i = 1; i < width; ++i) sum = Add(sum, Mul(a[i], b[i]));
  return sum;
}

// §3.1: scalar instructions read the w lane of the (swizzled) source; the spec marks the lane
// unconfirmed and the README's table documents w.
float Scalar(const Vec4& source) { return source[3]; }

// §3.3 lit: 127.9961f, the largest 8.8 fixed-point value, as the spec gives its bits.
const float kLitMaxPower = std::bit_cast<float>(0x42FFFE01u);

struct MatrixShape {
  int rows;
  int width;  // dp4 or dp3 per row
};

std::optional<MatrixShape> MatrixShapeOf(Opcode opcode) {
  switch (opcode) {
    case Opcode::kM4x4: return MatrixShape{4, 4};
    case Opcode::kM4x3: return MatrixShape{3, 4};
    case Opcode::kM3x4: return MatrixShape{4, 3};
    case Opcode::kM3x3: return MatrixShape{3, 3};
    case Opcode::kM3x2: return MatrixShape{2, 3};
    default: return std::nullopt;
  }
}

Result Lit(const Vec4& a) {
  Result r = {Bits(1.0f, "lit: r.x = 1"), Bits(a[0] > 0 ? a[0] : 0.0f, "lit: r.y = a.x if a.x > 0, else 0"),
              Bits(0.0f, "lit: r.z = 0 unless a.x > 0 and a.y > 0"), Bits(1.0f, "lit: r.w = 1")};
  if (!(a[0] > 0 && a[1] > 0)) return r;
  if (std::isnan(a[3])) {
    r[2] = Unspecified("lit: the spec's clamp of the power to +-127.9961 does not say what a NaN power gives");
    return r;
  }
  const float power = std::clamp(a[3], -kLitMaxPower, kLitMaxPower);
  if (std::isinf(a[1]) && power == 0) {
    r[2] = Unspecified("lit: pow(inf, 0) is 1, but the exp2(power * log2(a.y)) form the spec allows gives NaN");
    return r;
  }
  // "At least 8 fractional bits in the power; error comparable to a logp+expp pair": the model asks
  // for 10 bits, as expp/logp's partial precision does (stricter than 8 bits of the power allows for
  // large powers).
  r[2] = Within(std::pow(static_cast<double>(a[1]), static_cast<double>(power)), TwoTo(-10), kDenormalStep,
                "lit: r.z = pow(a.y, clamp(a.w, +-127.9961)), about 10 bits");
  return r;
}

Result Expp(const Vec4& a) {
  const float w = Scalar(a);
  // r.z: the spec's 2^-11 is an absolute error (a relative one for large values); clearing the 8 low
  // bits of a denormal result, as the spec's reference code does, loses up to 2^-141.
  const double whole = std::floor(static_cast<double>(w));
  const Expected z =
      std::isnan(w) ? Value(w, "expp: r.z = 2^NaN")
                    : Within(std::exp2(static_cast<double>(w)), TwoTo(-11), TwoTo(-141),
                             "expp: r.z = 2^w to 11 bits, the 8 low mantissa bits cleared", /*low_byte_clear=*/true);
  return {Value(std::exp2(whole), "expp: r.x = 2^floor(w), an exact power of two"),
          Value(static_cast<double>(w) - whole, "expp: r.y = w - floor(w)"), z, Bits(1.0f, "expp: r.w = 1")};
}

Result Logp(const Vec4& a) {
  const float v = std::fabs(Scalar(a));
  if (v == 0) {
    return {Bits(-FLT_MAX, "logp(0).x = -FLT_MAX"), Bits(1.0f, "logp(0).y = 1 (the spec's code, README)"),
            Bits(-FLT_MAX, "logp(0).z = -FLT_MAX"), Bits(1.0f, "logp: r.w = 1")};
  }
  // §3.3: the DX8 split form (the README's reading of this unconfirmed item), bit by bit.
  const std::uint32_t bits = std::bit_cast<std::uint32_t>(v);
  const Expected z =
      std::isnan(v) ? Value(v, "logp: r.z = log2(NaN)")
                    : Within(std::log2(static_cast<double>(v)), TwoTo(-10), TwoTo(-10),
                             "logp: r.z = log2|w| to 10 bits, the 8 low mantissa bits cleared", /*low_byte_clear=*/true);
  return {Bits(static_cast<float>(static_cast<int>(bits >> 23) - 127), "logp: r.x = unbiased exponent of |w|"),
          Bits(std::bit_cast<float>((bits & 0x007FFFFFu) | 0x3F800000u), "logp: r.y = mantissa of |w| in [1, 2)"), z,
          Bits(1.0f, "logp: r.w = 1")};
}

}  // namespace

std::optional<Result> Model(Opcode opcode, const Operands& v) {
  const Vec4& a = v[0];
  const Vec4& b = v[1];
  const Vec4& c = v[2];
  Result r;
  const auto each_lane = [&r](auto lane) {
    for (int i = 0; i < 4; ++i) r[i] = lane(i);
    return r;
  };
  switch (opcode) {
    case Opcode::kNop:
    case Opcode::kDcl:
    case Opcode::kDef:
    // The later models' rows: this model is vs_1_1's (their semantics are not written yet).
    case Opcode::kLrp: case Opcode::kCall: case Opcode::kCallnz: case Opcode::kLoop: case Opcode::kRet:
    case Opcode::kEndloop: case Opcode::kLabel: case Opcode::kPow: case Opcode::kCrs: case Opcode::kSgn:
    case Opcode::kAbs: case Opcode::kNrm: case Opcode::kSincos: case Opcode::kRep: case Opcode::kEndrep:
    case Opcode::kIf: case Opcode::kElse: case Opcode::kEndif: case Opcode::kMova: case Opcode::kDefb:
    case Opcode::kDefi: case Opcode::kIfc: case Opcode::kBreak: case Opcode::kBreakc: case Opcode::kSetp:
    case Opcode::kBreakp: case Opcode::kTexldl:
      return std::nullopt;
    case Opcode::kMov:
      return each_lane([&](int i) { return Bits(a[i], "mov: r = a"); });
    case Opcode::kAdd:
      return each_lane([&](int i) { return Value(static_cast<double>(a[i]) + b[i], "add: r = a + b"); });
    case Opcode::kSub:
      return each_lane([&](int i) { return Value(static_cast<double>(a[i]) - b[i], "sub: r = a - b"); });
    case Opcode::kMul:
      return each_lane([&](int i) { return Value(static_cast<double>(a[i]) * b[i], "mul: r = a * b"); });
    case Opcode::kMad:
      // "No fused-rounding requirement documented": two float operations, as everywhere in §3.1.
      return each_lane([&](int i) { return Value(static_cast<double>(Mul(a[i], b[i])) + c[i], "mad: r = a * b + c"); });
    case Opcode::kMin:
      return each_lane([&](int i) { return Bits(a[i] < b[i] ? a[i] : b[i], "min: a < b ? a : b"); });
    case Opcode::kMax:
      return each_lane([&](int i) { return Bits(a[i] >= b[i] ? a[i] : b[i], "max: a >= b ? a : b"); });
    case Opcode::kSlt:
      return each_lane([&](int i) { return Bits(a[i] < b[i] ? 1.0f : 0.0f, "slt: a < b ? 1 : 0"); });
    case Opcode::kSge:
      return each_lane([&](int i) { return Bits(a[i] >= b[i] ? 1.0f : 0.0f, "sge: a >= b ? 1 : 0"); });
    case Opcode::kDp3:
      return Replicated(Value(Dot(a, b, 3), "dp3: a.x*b.x + a.y*b.y + a.z*b.z"));
    case Opcode::kDp4:
      return Replicated(Value(Dot(a, b, 4), "dp4: a.x*b.x + a.y*b.y + a.z*b.z + a.w*b.w"));
    case Opcode::kRcp: {
      const float f = Scalar(a);
      if (std::isnan(f)) return Replicated(Value(f, "rcp: 1/NaN"));
      if (f == 1) return Replicated(Bits(1.0f, "rcp: 1 gives exactly 1"));
      if (f == 0) return Replicated(Bits(FLT_MAX, "rcp: +-0 gives +FLT_MAX (the spec's code, README)"));
      return Replicated(Within(1.0 / f, TwoTo(-22), kDenormalStep, "rcp: 1/f, error within 2^-22"));
    }
    case Opcode::kRsq: {
      const float f = std::fabs(Scalar(a));
      if (std::isnan(f)) return Replicated(Value(f, "rsq: NaN"));
      if (f == 1) return Replicated(Bits(1.0f, "rsq: 1 gives exactly 1"));
      if (f == 0) return Replicated(Bits(FLT_MAX, "rsq: +-0 gives +FLT_MAX (the spec's code, README)"));
      return Replicated(Within(1.0 / std::sqrt(static_cast<double>(f)), TwoTo(-22), kDenormalStep,
                               "rsq: 1/sqrt|f|, error within 2^-22"));
    }
    case Opcode::kExp: {
      const float f = Scalar(a);
      if (std::isnan(f)) return Replicated(Value(f, "exp: 2^NaN"));
      return Replicated(Within(std::exp2(static_cast<double>(f)), TwoTo(-21), kDenormalStep, "exp: 2^v to 21 bits"));
    }
    case Opcode::kLog: {
      const float f = std::fabs(Scalar(a));
      if (std::isnan(f)) return Replicated(Value(f, "log: log2(NaN)"));
      if (f == 0) return Replicated(Bits(-FLT_MAX, "log: 0 gives -FLT_MAX (the spec's code, README)"));
      // 21 bits; near v = 1, where log2 v is near 0, as an absolute error.
      return Replicated(Within(std::log2(static_cast<double>(f)), TwoTo(-21), TwoTo(-21), "log: log2|v| to 21 bits"));
    }
    case Opcode::kLit:
      return Lit(a);
    case Opcode::kDst:
      return Result{Bits(1.0f, "dst: r.x = 1"), Value(static_cast<double>(a[1]) * b[1], "dst: r.y = a.y * b.y"),
                    Bits(a[2], "dst: r.z = a.z"), Bits(b[3], "dst: r.w = b.w")};
    case Opcode::kFrc:
      // r = a - floor(a) as one float subtraction. The spec also says the result lies in [0, 1); for a
      // tiny negative a the formula gives 1.0 (1 - 1e-30 rounds to 1), and the model follows the formula.
      r = each_lane([&](int i) {
        return Value(static_cast<double>(a[i]) - std::floor(static_cast<double>(a[i])), "frc: a - floor(a)");
      });
      r[2] = r[3] = Expected();  // frc writes x and y only
      return r;
    case Opcode::kExpp:
      return Expp(a);
    case Opcode::kLogp:
      return Logp(a);
    case Opcode::kM4x4:
    case Opcode::kM4x3:
    case Opcode::kM3x4:
    case Opcode::kM3x3:
    case Opcode::kM3x2: {
      const MatrixShape shape = *MatrixShapeOf(opcode);
      for (int row = 0; row < shape.rows; ++row) {
        r[row] = Value(Dot(a, v[1 + row], shape.width), "matrix row: dp of s0 with register s1 + row");
      }
      return r;
    }
  }
  return std::nullopt;
}

bool Accepts(const Expected& expected, float actual, std::string& why) {
  std::ostringstream message;
  const std::uint32_t actual_bits = std::bit_cast<std::uint32_t>(actual);
  message << std::hexfloat;
  bool ok = true;
  switch (expected.kind) {
    case Kind::kUnwritten:
    case Kind::kUnspecified:
      return true;
    case Kind::kBits:
      ok = actual_bits == std::bit_cast<std::uint32_t>(expected.value);
      message << "expected exactly " << expected.value << " (0x" << std::hex
              << std::bit_cast<std::uint32_t>(expected.value) << ")";
      break;
    case Kind::kValue:
      ok = std::isnan(expected.value) ? std::isnan(actual)
                                      : actual_bits == std::bit_cast<std::uint32_t>(expected.value);
      message << "expected " << expected.value << " (rounded once to float)";
      break;
    case Kind::kWithin: {
      message << "expected " << expected.exact << " within " << expected.relative << " relative + "
              << expected.absolute;
      if (std::isnan(actual)) {
        ok = false;
      } else if (expected.low_byte_clear && (actual_bits & 0xFFu) != 0) {
        ok = false;
        message << ", with the 8 low mantissa bits clear";
      } else if (std::isinf(expected.exact) || std::isinf(actual)) {
        // An infinity is right where the true value is one, or where the allowed range overflows.
        const double reach = std::fabs(expected.exact) * (1 + expected.relative) + expected.absolute;
        ok = std::signbit(actual) == std::signbit(expected.exact) && std::isinf(actual) &&
             (std::isinf(expected.exact) || reach > FLT_MAX);
      } else {
        ok = ErrorFraction(expected, actual) <= 1.0;
      }
      break;
    }
  }
  if (!ok) {
    message << ", got " << actual << " (0x" << std::hex << actual_bits << "); rule: " << expected.rule;
    why = message.str();
  }
  return ok;
}

double ErrorFraction(const Expected& expected, float actual) {
  if (expected.kind != Kind::kWithin || std::isinf(expected.exact) || std::isinf(actual)) return 0.0;
  const double allowed = expected.relative * std::fabs(expected.exact) + expected.absolute;
  return std::fabs(static_cast<double>(actual) - expected.exact) / allowed;
}

}  // namespace vs11::model
