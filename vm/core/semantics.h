// The arithmetic of every vs_1_1 instruction, written once as templates over a lane type V.
// The reference engine instantiates them with V = float (one vertex); the batch engine with a Highway
// vector (many vertices). Both engines therefore round identically, which is what makes them equal bit
// for bit. Kernels use only the operations below; a lane type provides them as free functions found by
// ordinary or argument-dependent lookup (Highway's own ops for its vectors, the float overloads here).
//
// Source of every formula: ../shared/spec/vs_1_1.md §3.3.
#pragma once

#include <array>
#include <bit>
#include <cfloat>
#include <cmath>
#include <cstdint>

#include "vm/core/float_rules.h"

namespace vs11::semantics {

template <class V>
using Vec4 = std::array<V, 4>;

// ---- float lane operations ------------------------------------------------------------------------
inline float Floor(float x) { return std::floor(x); }
inline float Sqrt(float x) { return std::sqrt(x); }
inline float Abs(float x) { return std::fabs(x); }
// -x with the sign bit flipped, NaNs included (a source's negate modifier).
inline float Negate(float x) {
  float negated = -x;
#if defined(__x86_64__)
  // As the batch kernels' Negate: keeps the compiler from folding a + (-b) into a - b, which would
  // return b's NaN with its sign unflipped (seen once FetchSource became visible to the tracer and
  // GCC inlined it differently).
  asm("" : "+x"(negated));
#endif
  return negated;
}
inline bool IsNaN(float x) { return x != x; }
inline float IfThenElse(bool condition, float yes, float no) { return condition ? yes : no; }
inline float Constant(float /*like*/, float value) { return value; }
inline std::int32_t ConstantInt(float /*like*/, std::int32_t value) { return value; }
inline std::int32_t BitsOf(float x) { return std::bit_cast<std::int32_t>(x); }
inline float FloatFromBits(std::int32_t bits) { return std::bit_cast<float>(bits); }
// Truncates; callers guarantee the value is an integer within int32 range.
inline std::int32_t ToInt(float x) { return static_cast<std::int32_t>(x); }
inline float ToFloat(std::int32_t x) { return static_cast<float>(x); }
template <int kBits>
std::int32_t ShiftLeft(std::int32_t x) { return static_cast<std::int32_t>(static_cast<std::uint32_t>(x) << kBits); }
template <int kBits>
std::int32_t ShiftRight(std::int32_t x) { return x >> kBits; }  // arithmetic (C++20)

// ---- named constants ------------------------------------------------------------------------------
inline constexpr float kMaxFloat = FLT_MAX;            // rcp/rsq of 0, log of 0 (negated): §3.3, §8
inline constexpr float kLitMaxPower = 127.9961f;       // 0x42FFFE01, the largest 8.8 fixed-point value
inline constexpr std::int32_t kPartialPrecisionMask = static_cast<std::int32_t>(0xFFFFFF00u);  // expp/logp z
inline constexpr std::int32_t kMantissaMask = 0x007FFFFF;
inline constexpr std::int32_t kOneExponentBits = 0x3F800000;  // 1.0f: mantissa in [1, 2)
inline constexpr int kMantissaBits = 23;
inline constexpr std::int32_t kExponentBias = 127;

// ---- transcendental helpers, shared so both engines round alike ------------------------------------

// 2^e for an integral e in [-150, 128], as two exact power-of-two factors (each a normal float), so
// results underflow and overflow the way a single IEEE multiply would.
template <class V, class I>
V ScaleByPowerOfTwo(V value, I e) {
  I half = ShiftRight<1>(e);
  I rest = e - half;
  I bias = ConstantInt(value, kExponentBias);
  V first = FloatFromBits(ShiftLeft<kMantissaBits>(half + bias));
  V second = FloatFromBits(ShiftLeft<kMantissaBits>(rest + bias));
  return (value * first) * second;
}

// Largest and smallest exponents worth computing: beyond them 2^x is +inf or rounds to +0.
inline constexpr float kExp2Max = 128.0f;
inline constexpr float kExp2Min = -150.0f;

// 2^x to about 23 bits (spec asks 21): x = n + f with |f| <= 1/2, 2^f by its Taylor series to f^7
// (truncation error (ln2/2)^8/8! < 1e-8), then scaled by 2^n. NaN gives NaN, +inf gives +inf, -inf 0.
template <class V>
V Exp2(V x) {
  V clamped = IfThenElse(x < Constant(x, kExp2Max), x, Constant(x, kExp2Max));
  clamped = IfThenElse(clamped > Constant(x, kExp2Min), clamped, Constant(x, kExp2Min));
  V whole = Floor(clamped + Constant(x, 0.5f));
  V f = clamped - whole;
  // Coefficients (ln 2)^k / k!.
  V p = Constant(x, 1.52527338e-5f);
  p = p * f + Constant(x, 1.54035304e-4f);
  p = p * f + Constant(x, 1.33335581e-3f);
  p = p * f + Constant(x, 9.61812911e-3f);
  p = p * f + Constant(x, 5.55041087e-2f);
  p = p * f + Constant(x, 2.40226507e-1f);
  p = p * f + Constant(x, 6.93147181e-1f);
  p = p * f + Constant(x, 1.0f);
  V result = ScaleByPowerOfTwo(p, ToInt(whole));
  // x + x: a NaN comes out quiet, as from any IEEE operation. Passed through as it is, a signalling
  // NaN whose payload sits in the 8 low bits would become +inf under expp's PartialPrecision mask.
  return IfThenElse(IsNaN(x), x + x, result);
}

// log2(v) for v >= 0 to about 23 bits (spec asks 21): v = 2^e m with m in [sqrt(1/2), sqrt(2)), and
// log2(m) = (2 / ln 2) atanh(t), t = (m - 1) / (m + 1), |t| < 0.172, by its odd series to t^9.
// Denormals are scaled up first. 0 gives -FLT_MAX (§3.3 log), +inf gives +inf, NaN gives NaN.
template <class V>
V Log2(V v) {
  const V kSmallestNormal = Constant(v, FLT_MIN);
  auto denormal = v < kSmallestNormal;
  V scaled = IfThenElse(denormal, v * Constant(v, 16777216.0f), v);  // 2^24
  V exponent_offset = IfThenElse(denormal, Constant(v, 24.0f), Constant(v, 0.0f));
  auto bits = BitsOf(scaled);
  V e = ToFloat(ShiftRight<kMantissaBits>(bits) - ConstantInt(v, kExponentBias)) - exponent_offset;
  V m = FloatFromBits((bits & ConstantInt(v, kMantissaMask)) | ConstantInt(v, kOneExponentBits));
  auto above_sqrt2 = m > Constant(v, 1.41421356f);
  m = IfThenElse(above_sqrt2, m * Constant(v, 0.5f), m);
  e = IfThenElse(above_sqrt2, e + Constant(v, 1.0f), e);
  V t = (m - Constant(v, 1.0f)) / (m + Constant(v, 1.0f));
  V t2 = t * t;
  // 2 / (k ln 2) for k = 9, 7, 5, 3, 1.
  V p = Constant(v, 0.320598898f);
  p = p * t2 + Constant(v, 0.412198583f);
  p = p * t2 + Constant(v, 0.577078016f);
  p = p * t2 + Constant(v, 0.961796694f);
  p = p * t2 + Constant(v, 2.88539008f);
  V result = e + p * t;
  result = IfThenElse(v == Constant(v, 0.0f), Constant(v, -kMaxFloat), result);
  result = IfThenElse(v == Constant(v, INFINITY), v, result);
  return IfThenElse(IsNaN(v), v + v, result);  // quiet, as in Exp2 (logp's PartialPrecision)
}

// Clears the low 8 mantissa bits, as the reference rasterizer did for expp/logp's partial result.
template <class V>
V PartialPrecision(V x) {
  return FloatFromBits(BitsOf(x) & ConstantInt(x, kPartialPrecisionMask));
}

// A product an instruction computes from its operands: mul, mad, dp3, dp4, the matrices, dst.y and
// lit's power, under the float rules the engine or translation was made with (vm/core/float_rules.h).
// The transcendental helpers' own multiplications stay plain. kRules is a template argument so that
// each rule is compiled in: d3d9's products are the bare multiply they always were, with no test.
//
// kLegacy is DXVK's form, compares and selects that every lane type already has: an operand is
// replaced by +0 where the other is zero, so 0 * inf and 0 * NaN give 0. The sign of a zero result
// follows from the form: the zero operand's own sign when the other is not zero, +0 when both are.
template <FloatRules kRules, class V>
V Product(V a, V b) {
  if constexpr (kRules == FloatRules::kLegacy) {
    const V zero = Constant(a, 0.0f);
    return IfThenElse(b == zero, zero, a) * IfThenElse(a == zero, zero, b);
  } else {
    return a * b;
  }
}

template <FloatRules kRules, class V, int kWidth>
V Dot(const Vec4<V>& a, const Vec4<V>& b) {
  V sum = Product<kRules>(a[0], b[0]);
  for (int i = 1; i < kWidth; ++i) sum = sum + Product<kRules>(a[i], b[i]);  // left to right, unfused
  return sum;
}

// ---- per-opcode kernels ---------------------------------------------------------------------------
// One struct per row of VS11_OPCODES (vm/core/isa.h), named <Name>Semantics. Its member matches the row's
// ResultKind: Lane (componentwise), Scalar (scalar: one value from the source's w lane), Vector
// (vector). Dot products and matrices use Dot above with the row's dot width; nop/dcl/def do nothing.
// A member that computes products takes the float rules as its first template argument
// (FollowsFloatRules below); the engines call every member through RunLane and RunVector.

struct NopSemantics {};
struct DclSemantics {};
struct DefSemantics {};
struct Dp3Semantics {};
struct Dp4Semantics {};
struct M4x4Semantics {};
struct M4x3Semantics {};
struct M3x4Semantics {};
struct M3x3Semantics {};
struct M3x2Semantics {};
// The later models' rows without arithmetic: flow control (run by the reference engine's program
// counter, vm/engines/reference_flow.cc), definitions, and texldl (vm/core/texture_sampling.h). if_comp,
// break_comp and setp_comp compare with Compare below.
struct CallSemantics {};
struct CallnzSemantics {};
struct LoopSemantics {};
struct RetSemantics {};
struct EndloopSemantics {};
struct LabelSemantics {};
struct RepSemantics {};
struct EndrepSemantics {};
struct IfSemantics {};
struct ElseSemantics {};
struct EndifSemantics {};
struct DefbSemantics {};
struct DefiSemantics {};
struct IfcSemantics {};
struct BreakSemantics {};
struct BreakcSemantics {};
struct SetpSemantics {};
struct BreakpSemantics {};
struct TexldlSemantics {};

struct MovSemantics {
  template <class V> static V Lane(V a, V, V) { return a; }
};
struct AddSemantics {
  template <class V> static V Lane(V a, V b, V) { return a + b; }
};
struct SubSemantics {
  template <class V> static V Lane(V a, V b, V) { return a - b; }
};
struct MulSemantics {
  template <FloatRules kRules, class V> static V Lane(V a, V b, V) { return Product<kRules>(a, b); }
};
struct MadSemantics {
  // Unfused (-ffp-contract=off; the jit emits a multiply and an add).
  template <FloatRules kRules, class V> static V Lane(V a, V b, V c) { return Product<kRules>(a, b) + c; }
};
struct MinSemantics {
  template <class V> static V Lane(V a, V b, V) { return IfThenElse(a < b, a, b); }
};
struct MaxSemantics {
  template <class V> static V Lane(V a, V b, V) { return IfThenElse(a >= b, a, b); }
};
struct SltSemantics {
  template <class V> static V Lane(V a, V b, V) { return IfThenElse(a < b, Constant(a, 1.0f), Constant(a, 0.0f)); }
};
struct SgeSemantics {
  template <class V> static V Lane(V a, V b, V) { return IfThenElse(a >= b, Constant(a, 1.0f), Constant(a, 0.0f)); }
};
struct FrcSemantics {
  template <class V> static V Lane(V a, V, V) { return a - Floor(a); }
};

struct RcpSemantics {
  template <class V> static V Scalar(V f) {
    V result = Constant(f, 1.0f) / f;
    result = IfThenElse(f == Constant(f, 0.0f), Constant(f, kMaxFloat), result);  // -0 too
    return IfThenElse(f == Constant(f, 1.0f), Constant(f, 1.0f), result);
  }
};
struct RsqSemantics {
  template <class V> static V Scalar(V s) {
    V f = Abs(s);
    V result = Constant(f, 1.0f) / Sqrt(f);
    result = IfThenElse(f == Constant(f, 0.0f), Constant(f, kMaxFloat), result);
    return IfThenElse(f == Constant(f, 1.0f), Constant(f, 1.0f), result);
  }
};
struct ExpSemantics {
  template <class V> static V Scalar(V f) { return Exp2(f); }
};
struct LogSemantics {
  template <class V> static V Scalar(V f) { return Log2(Abs(f)); }
};

struct LitSemantics {
  template <FloatRules kRules, class V> static Vec4<V> Vector(const Vec4<V>& a, const Vec4<V>&) {
    const V zero = Constant(a[0], 0.0f), one = Constant(a[0], 1.0f);
    V power = IfThenElse(a[3] < Constant(a[0], kLitMaxPower), a[3], Constant(a[0], kLitMaxPower));
    power = IfThenElse(power > Constant(a[0], -kLitMaxPower), power, Constant(a[0], -kLitMaxPower));
    V specular = Exp2(Product<kRules>(power, Log2(a[1])));
    auto lit = a[0] > zero;
    return {one, IfThenElse(lit, a[0], zero), IfThenElse(lit, IfThenElse(a[1] > zero, specular, zero), zero), one};
  }
};
struct DstSemantics {
  template <FloatRules kRules, class V> static Vec4<V> Vector(const Vec4<V>& a, const Vec4<V>& b) {
    return {Constant(a[0], 1.0f), Product<kRules>(a[1], b[1]), a[2], b[3]};
  }
};
struct ExppSemantics {
  template <class V> static Vec4<V> Vector(const Vec4<V>& a, const Vec4<V>&) {
    V w = a[3];
    V whole = Floor(w);
    // 2^floor(w) exactly: the clamp only decides where it saturates to +inf or 0.
    V clamped = IfThenElse(whole < Constant(w, kExp2Max), whole, Constant(w, kExp2Max));
    clamped = IfThenElse(clamped > Constant(w, kExp2Min), clamped, Constant(w, kExp2Min));
    V power = ScaleByPowerOfTwo(Constant(w, 1.0f), ToInt(IfThenElse(IsNaN(w), Constant(w, 0.0f), clamped)));
    power = IfThenElse(IsNaN(w), w, power);
    return {power, w - whole, PartialPrecision(Exp2(w)), Constant(w, 1.0f)};
  }
};
struct LogpSemantics {
  template <class V> static Vec4<V> Vector(const Vec4<V>& a, const Vec4<V>&) {
    V v = Abs(a[3]);
    auto bits = BitsOf(v);
    V exponent = ToFloat(ShiftRight<kMantissaBits>(bits) - ConstantInt(v, kExponentBias));
    V mantissa = FloatFromBits((bits & ConstantInt(v, kMantissaMask)) | ConstantInt(v, kOneExponentBits));
    auto zero = v == Constant(v, 0.0f);
    const V lowest = Constant(v, -kMaxFloat), one = Constant(v, 1.0f);
    return {IfThenElse(zero, lowest, exponent), IfThenElse(zero, one, mantissa),
            IfThenElse(zero, lowest, PartialPrecision(Log2(v))), one};
  }
};

// ---- the later models' arithmetic (vs_2_0 on) -------------------------------------------------------
// Source of every formula: Microsoft's D3D9 reference pages for each instruction (the README's "Shader
// models" section lists the facts). Where the reference leaves the bits open (pow, sincos, mova's ties, sgn's NaN), the
// choice is said at the kernel and in the README's "Shader models" section.

struct AbsSemantics {
  template <class V> static V Lane(V a, V, V) { return Abs(a); }
};
struct LrpSemantics {
  // s0 * (s1 - s2) + s2, unfused, as the reference's formula orders it.
  template <FloatRules kRules, class V> static V Lane(V a, V b, V c) { return Product<kRules>(a, b - c) + c; }
};
// -1, 0 or 1. Both zeros give +0; NaN fails both tests and gives 1, the reference's "else" case read
// literally. vs_2_0's two scratch temporaries (s1, s2) are left unchanged: their contents are undefined.
struct SgnSemantics {
  template <class V> static V Lane(V a, V, V) {
    const V zero = Constant(a, 0.0f);
    return IfThenElse(a < zero, Constant(a, -1.0f), IfThenElse(a == zero, zero, Constant(a, 1.0f)));
  }
};
// mova: the nearest integer, ties away from zero (x.5 -> x+1, -x.5 -> -(x+1)). Microsoft's reference
// says only "RoundToNearest", so the tie rule is our choice (unconfirmed on hardware), tested against
// the other reading (ties to even) in tests/vm/core/later_model_semantics_test.cc. The fraction is
// taken as |x| - floor(|x|), which is exact, rather than floor(|x| + 0.5), whose sum rounds up for
// 0.49999997. The engine then clamps the integer as vs_1_1's a0 (AddressFromFloat: NaN -> -2^20).
struct MovaSemantics {
  template <class V> static V Lane(V a, V, V) {
    const V magnitude = Abs(a);
    const V whole = Floor(magnitude);
    const V rounded = IfThenElse(magnitude - whole >= Constant(a, 0.5f), whole + Constant(a, 1.0f), whole);
    return IfThenElse(a < Constant(a, 0.0f), Negate(rounded), rounded);
  }
};
// _sat on a destination (vs_2_0 on): the result clamped to [0, 1]; NaN and -0 give +0.
template <class V>
V Saturate(V v) {
  const V zero = Constant(v, 0.0f), one = Constant(v, 1.0f);
  return IfThenElse(v > zero, IfThenElse(v < one, v, one), zero);
}
// if_comp, break_comp and setp_comp's test (Instruction::comparison: 1 gt, 2 eq, 3 ge, 4 lt, 5 ne,
// 6 le): 1 where it holds, else 0. Every comparison with a NaN is false except ne.
template <class V>
V Compare(int comparison, V a, V b) {
  const V one = Constant(a, 1.0f), zero = Constant(a, 0.0f);
  switch (comparison) {
    case 1: return IfThenElse(a > b, one, zero);
    case 2: return IfThenElse(a == b, one, zero);
    case 3: return IfThenElse(a >= b, one, zero);
    case 4: return IfThenElse(a < b, one, zero);
    case 5: return IfThenElse(a == b, zero, one);
    case 6: return IfThenElse(b >= a, one, zero);
    default: return zero;
  }
}

// Compare with the comparison fixed, as a componentwise kernel (the batch engine's setp steps).
template <int kComparison>
struct CompareSemantics {
  template <class V> static V Lane(V a, V b, V) { return Compare(kComparison, a, b); }
};

// A predicated write (vs_2_x's `(p0.c) op` and the execution masks batch and jit run dynamic flow
// with): `value` where the predicate lane holds (1, as Compare gives; 0 where it does not), `old`
// elsewhere; `!p0` the other way round.
template <class V>
V PredicatedWrite(V predicate, bool negated, V value, V old) {
  const auto on = predicate == Constant(predicate, 1.0f);
  return negated ? IfThenElse(on, old, value) : IfThenElse(on, value, old);
}
template <bool kNegated>
struct PredicatedWriteSemantics {
  template <class V> static V Lane(V predicate, V value, V old) { return PredicatedWrite(predicate, kNegated, value, old); }
};

// pow: |s0|^s1 as exp2(s1 * log2|s0|) with the float rules' Exp2 and Log2 above and the product under
// kRules, lit's specular power without its clamp. Reads the w lane of each (replicate-swizzled) source,
// as vs_1_1's scalar instructions do, and replicates. 0^0 = 1, 0^y = 0 for y > 0, +inf for y < 0
// (log2 0 = -FLT_MAX); exact for powers of two raised to integers (log2 and exp2 are exact there).
struct PowSemantics {
  template <FloatRules kRules, class V> static Vec4<V> Vector(const Vec4<V>& a, const Vec4<V>& b) {
    const V power = Exp2(Product<kRules>(b[3], Log2(Abs(a[3]))));
    return {power, power, power, power};
  }
};
// crs: the cross product of the xyz lanes; w is never written (the engine limits the mask to xyz).
struct CrsSemantics {
  template <FloatRules kRules, class V> static Vec4<V> Vector(const Vec4<V>& a, const Vec4<V>& b) {
    return {Product<kRules>(a[1], b[2]) - Product<kRules>(a[2], b[1]),
            Product<kRules>(a[2], b[0]) - Product<kRules>(a[0], b[2]),
            Product<kRules>(a[0], b[1]) - Product<kRules>(a[1], b[0]), Constant(a[0], 0.0f)};
  }
};
// nrm: src * (1 / sqrt(x^2 + y^2 + z^2)), w scaled too; a zero length scales by FLT_MAX (so a zero
// vector stays zero in xyz and a nonzero w becomes +-inf).
struct NrmSemantics {
  template <FloatRules kRules, class V> static Vec4<V> Vector(const Vec4<V>& a, const Vec4<V>&) {
    const V f = Dot<kRules, V, 3>(a, a);
    const V scale = IfThenElse(f == Constant(f, 0.0f), Constant(f, kMaxFloat), Constant(f, 1.0f) / Sqrt(f));
    return {Product<kRules>(a[0], scale), Product<kRules>(a[1], scale), Product<kRules>(a[2], scale),
            Product<kRules>(a[3], scale)};
  }
};

// sin and cos of x to about 1e-7 absolute, from + - * and Floor alone so that every lane type computes
// the same bits: x reduced to r in [-pi, pi] (2 pi split in two parts so that r is exact for |x| up to
// a few thousand), then h = r / 2 in [-pi/2, pi/2], sin h and cos h by their Taylor series to h^11 and
// h^12 (truncation below 6e-8), and sin r = 2 sin h cos h, cos r = cos^2 h - sin^2 h. NaN and +-inf
// give NaN. The reference's own D3DSINCOSCONST series is not used: it is accurate on [-pi, pi] only to
// about 1e-3, and hardware computes sin and cos its own way.
template <class V>
std::array<V, 2> CosSin(V x) {
  const V turns = Floor(x * Constant(x, 0.159154943f) + Constant(x, 0.5f));
  const V r = (x - turns * Constant(x, 6.28125f)) - turns * Constant(x, 1.93530718e-3f);
  const V h = r * Constant(x, 0.5f);
  const V h2 = h * h;
  V s = Constant(x, -2.50521084e-8f);  // -1/11!
  s = s * h2 + Constant(x, 2.75573192e-6f);
  s = s * h2 + Constant(x, -1.98412698e-4f);
  s = s * h2 + Constant(x, 8.33333333e-3f);
  s = s * h2 + Constant(x, -1.66666667e-1f);
  s = (s * h2) * h + h;
  V c = Constant(x, 2.08767570e-9f);  // 1/12!
  c = c * h2 + Constant(x, -2.75573192e-7f);
  c = c * h2 + Constant(x, 2.48015873e-5f);
  c = c * h2 + Constant(x, -1.38888889e-3f);
  c = c * h2 + Constant(x, 4.16666667e-2f);
  c = c * h2 + Constant(x, -0.5f);
  c = c * h2 + Constant(x, 1.0f);
  return {c * c - s * s, Constant(x, 2.0f) * s * c};
}
// sincos: x = cos, y = sin of the source's w lane (the source is replicate-swizzled); z and w are never
// written (the engine limits the mask to xy). vs_2_0's two constant operands are not read: the result
// does not depend on them.
struct SincosSemantics {
  template <class V> static Vec4<V> Vector(const Vec4<V>& a, const Vec4<V>&) {
    const std::array<V, 2> cos_sin = CosSin(a[3]);
    return {cos_sin[0], cos_sin[1], Constant(a[3], 0.0f), Constant(a[3], 0.0f)};
  }
};

// ---- calling a kernel ------------------------------------------------------------------------------
// Whether a kernel depends on the float rules is written once, in its member's signature: these
// concepts read it, and RunLane and RunVector pass the rules to the members that take them. The
// batch engine compiles a second kernel only for a kernel that follows them.

template <class Semantics>
concept FollowsFloatRules =
    requires(float v) { Semantics::template Lane<FloatRules::kD3d9>(v, v, v); } ||
    requires(const Vec4<float>& v) { Semantics::template Vector<FloatRules::kD3d9>(v, v); };

template <class Semantics, class V>
concept HasLane = requires(V v) { Semantics::Lane(v, v, v); } ||
                  requires(V v) { Semantics::template Lane<FloatRules::kD3d9>(v, v, v); };
template <class Semantics, class V>
concept HasScalar = requires(V v) { Semantics::Scalar(v); };
template <class Semantics, class V>
concept HasVector = requires(const Vec4<V>& v) { Semantics::Vector(v, v); } ||
                    requires(const Vec4<V>& v) { Semantics::template Vector<FloatRules::kD3d9>(v, v); };

template <FloatRules kRules, class Semantics, class V>
V RunLane(V a, V b, V c) {
  if constexpr (FollowsFloatRules<Semantics>) {
    return Semantics::template Lane<kRules>(a, b, c);
  } else {
    return Semantics::Lane(a, b, c);
  }
}

template <FloatRules kRules, class Semantics, class V>
Vec4<V> RunVector(const Vec4<V>& a, const Vec4<V>& b) {
  if constexpr (FollowsFloatRules<Semantics>) {
    return Semantics::template Vector<kRules>(a, b);
  } else {
    return Semantics::Vector(a, b);
  }
}

}  // namespace vs11::semantics
