// Nine-coefficient (bands l <= 2) spherical-harmonic maths for irradiance, in double precision and
// independent of the vertex machine: the real basis of the paper's eq. (5), irradiance by eq. (6)
// and by the polynomial of eq. (7), and the packing of the coefficients into the seven vs_1_1
// constant registers of the paper's Table 1 (plus a shorter packing valid only on unit normals).
//
// Coefficient order (index = l (l + 1) + m):
//
//   index  0    1     2    3    4     5     6    7    8
//   (l,m)  0,0  1,-1  1,0  1,1  2,-2  2,-1  2,0  2,1  2,2
//   y_lm   1    y     z    x    xy    yz    3z^2-1   xz   x^2-y^2   (up to the constants kShN*)
#pragma once

#include <array>
#include <cassert>
#include <numbers>
#include <optional>
#include <span>
#include <string_view>

#include <glm/glm.hpp>

#include "vm/core/name_table.h"

namespace vs11::irradiance {

inline constexpr int kSh9Bands = 3;         // l = 0, 1, 2
inline constexpr int kSh9Coefficients = 9;  // (l_max + 1)^2

// Position of (l, m) in the coefficient arrays; 0 <= l <= 2, -l <= m <= l.
constexpr int ShIndex(int l, int m) { return l * (l + 1) + m; }

// Basis normalisation constants, paper section 3.2 (they are the factors of eq. (5)):
// n0 = 1 / (2 sqrt pi) = sqrt(1 / 4pi)            for y00
// n1 = sqrt 3 / (2 sqrt pi) = sqrt(3 / 4pi)       for y1-1, y10, y11
// n2 = sqrt 15 / (2 sqrt pi) = sqrt(15 / 4pi)     for y2-2, y2-1, y21
// n3 = sqrt 5 / (4 sqrt pi) = sqrt(5 / 16pi)      for y20
// n4 = sqrt 15 / (4 sqrt pi) = sqrt(15 / 16pi)    for y22
// sqrt 5 and sqrt 15 to double precision (std::numbers has only sqrt 2 and sqrt 3).
inline constexpr double kSqrt5 = 2.2360679774997896964;
inline constexpr double kSqrt15 = 3.8729833462074168852;
inline constexpr double kShN0 = 0.5 * std::numbers::inv_sqrtpi;
inline constexpr double kShN1 = 0.5 * std::numbers::sqrt3 * std::numbers::inv_sqrtpi;
inline constexpr double kShN2 = 0.5 * kSqrt15 * std::numbers::inv_sqrtpi;
inline constexpr double kShN3 = 0.25 * kSqrt5 * std::numbers::inv_sqrtpi;
inline constexpr double kShN4 = 0.25 * kSqrt15 * std::numbers::inv_sqrtpi;

// Clamped-cosine convolution factors per band, paper eq. (6) (Ramamoorthi & Hanrahan 2001):
// A0 = pi, A1 = 2 pi / 3, A2 = pi / 4.
inline constexpr double kShA0 = std::numbers::pi;
inline constexpr double kShA1 = 2.0 * std::numbers::pi / 3.0;
inline constexpr double kShA2 = std::numbers::pi / 4.0;
inline constexpr std::array<double, kSh9Bands> kShBandFactor = {kShA0, kShA1, kShA2};

// Polynomial coefficients of eq. (7), paper section 3.2: c0 = A0 n0, c1 = A1 n1, c2 = A2 n2,
// c3 = A2 n3, c4 = A2 n4.
inline constexpr double kShC0 = kShA0 * kShN0;
inline constexpr double kShC1 = kShA1 * kShN1;
inline constexpr double kShC2 = kShA2 * kShN2;
inline constexpr double kShC3 = kShA2 * kShN3;
inline constexpr double kShC4 = kShA2 * kShN4;

// Nine RGB coefficients L_lm (radiance times steradians, per channel), ordered as above.
struct Sh9Rgb {
  std::array<glm::dvec3, kSh9Coefficients> coefficients{};

  glm::dvec3& at(int l, int m) {
    assert(l >= 0 && l < kSh9Bands && m >= -l && m <= l);
    return coefficients[ShIndex(l, m)];
  }
  const glm::dvec3& at(int l, int m) const {
    assert(l >= 0 && l < kSh9Bands && m >= -l && m <= l);
    return coefficients[ShIndex(l, m)];
  }
};

// The nine real basis functions of eq. (5) (no Condon-Shortley sign) at `unit_direction`, in
// ShIndex order. The direction must be unit length for these to be the spherical harmonics; the
// polynomials are evaluated as written (y20 with 3z^2 - 1) for whatever vector is given.
std::array<double, kSh9Coefficients> ShBasis(glm::dvec3 unit_direction);

// Irradiance E(n) = sum_lm A_l L_lm y_lm(n), eq. (6): radiance integrated against max(0, n.l) over
// the sphere, without the k_d / pi of eq. (1). Same units as the coefficients (per channel).
// `n` is used as given (not normalised). Because y20 is evaluated as 3z^2 - 1, eq. (6) written this
// way is the very same polynomial as eq. (7), so the two agree for every vector, not only unit
// ones (up to rounding); only on unit vectors is it the band-limited irradiance.
glm::dvec3 IrradianceEq6(const Sh9Rgb& sh, glm::dvec3 n);

// The same irradiance by the paper's eq. (7), a quadratic polynomial in x, y, z:
//   c0 L00 - c3 L20 + c1 (L1-1 y + L10 z + L11 x) + c2 (L2-2 xy + L2-1 yz + L21 xz)
//   + 3 c3 L20 z^2 + c4 L22 (x^2 - y^2)
// (the printed first term "c0 R10" is a typo for c0 R00). Defined for any vector.
glm::dvec3 IrradianceEq7(const Sh9Rgb& sh, glm::dvec3 n);

// Root of the sum over m of L_lm^2 for one band (0..2) and one channel (0 = r, 1 = g, 2 = b).
// Invariant under rotations of the environment.
double BandNorm(const Sh9Rgb& sh, int band, int channel);

// Windowing of the coefficients against ringing (Sloan, "Stupid Spherical Harmonics (SH) Tricks",
// GDC 2008, section "Windowing"): band l is multiplied by a factor w_l in [0, 1] with w_0 = 1,
// which trades sharpness for less overshoot. A bright source smaller than the nine terms can hold
// makes the truncated irradiance dip below zero about 120 degrees away from it (down to -3.7 % of
// the peak for a point light); the windows below reduce or remove that dip.
enum class ShWindow {
  kNone,     // w_l = 1
  kHanning,  // w_l = (1 + cos(pi l / width)) / 2 for l < width, else 0
  kLanczos,  // w_l = sinc(l / width) = sin(pi l / width) / (pi l / width) for l < width, else 0
  kDering,   // Sloan's deringing: w_l = 1 / (1 + lambda l^2 (l + 1)^2) (the window minimising the
             // squared error plus lambda times the squared Laplacian), with the smallest lambda
             // that makes this environment's irradiance non-negative in every direction
  kNonNegative,  // not a window: the coefficients refitted, each on its own, to the nearest nine-term
                 // irradiance that is non-negative everywhere (FitNonNegative, irradiance/sh/nonneg_fit.h)
};

inline constexpr NameTable kShWindowNames("window", {
    Choice(ShWindow::kNone, "none"), Choice(ShWindow::kHanning, "hanning"),
    Choice(ShWindow::kLanczos, "lanczos", "of --window-width bands"),
    Choice(ShWindow::kDering, "dering", "the mildest window that makes the irradiance non-negative"),
    Choice(ShWindow::kNonNegative, "nonneg",
           "not a window: the nearest nine terms whose irradiance is non-negative everywhere")});
inline std::string_view ShWindowName(ShWindow window) { return kShWindowNames.Name(window); }

// w_0, w_1, w_2 of kHanning or kLanczos for a width > 0 (asserted) in bands; 1, 1, 1 for kNone.
// A width of 3 (l_max + 1) is the narrowest that keeps band 2; larger widths attenuate less.
// kDering and kNonNegative have no fixed factors (see DeringLambda, FitNonNegative); asserted.
std::array<double, kSh9Bands> ShWindowFactors(ShWindow window, double width);

// The factors 1 / (1 + lambda l^2 (l + 1)^2) for a lambda >= 0.
std::array<double, kSh9Bands> LaplacianWindowFactors(double lambda);

// Sloan's deringing for these coefficients: the smallest lambda (to within 1e-4 relative) of
// LaplacianWindowFactors for which the windowed irradiance of every channel is >= 0 (down to 1e-9 of
// the largest |E|, for rounding) at every one of `normals` (unit vectors, e.g. SphereNormals(2000));
// 0, i.e. no window, when the irradiance is already non-negative there. Any non-negative radiance is
// deringed by a finite lambda, because the windowed kernel of a point light becomes non-negative;
// coefficients that are not a non-negative radiance (their band 0 negative) may need an unbounded
// one, and then 1e6, the largest lambda tried, is returned. Cost: at most about 45 evaluations of eq. (7)
// at every normal (25 for a point light).
double DeringLambda(const Sh9Rgb& sh, std::span<const glm::dvec3> normals);

// The coefficients with band l multiplied by factors[l].
Sh9Rgb ApplyShWindow(const Sh9Rgb& sh, const std::array<double, kSh9Bands>& factors);

// The seven float4 constant registers fed to the vertex program, in the order of kNames.
struct SevenConstants {
  static constexpr std::array<const char*, 7> kNames = {"cAr", "cAg", "cAb", "cBr",
                                                        "cBg", "cBb", "cC"};
  static constexpr int kA = 0;  // cA_c is registers[kA + c] for channel c = 0, 1, 2
  static constexpr int kB = 3;  // cB_c is registers[kB + c]
  static constexpr int kC = 6;  // cC
  std::array<glm::vec4, 7> registers{};
};

// Table 1 of the paper, for the 11-instruction program
//   r1.c = dp4((x, y, z, 1), cA_c); r2 = (xy, yz, zz, zx); r3.c = dp4(r2, cB_c);
//   result.rgb = r1 + r3 + cC.rgb * (x^2 - y^2)
// cA_c = (c1 L11, c1 L1-1, c1 L10, c0 L00 - c3 L20), cB_c = (c2 L2-2, c2 L2-1, 3 c3 L20, c2 L21),
// cC = (c4 R22, c4 G22, c4 B22, 0). Every entry is computed in double and rounded to float once.
// The polynomial equals eq. (7) for any vector.
SevenConstants PackTable1(const Sh9Rgb& sh);

// Packing for a 10-instruction program, exact only on unit normals: eq. (7) with z^2 = 1 - x^2 - y^2,
//   r1.c = dp4((x, y, z, 1), cA_c); r2 = (xy, yz, zx, xx); r3.c = dp4(r2, cB_c);
//   result.rgb = r1 + r3 + cC.rgb * yy
// cA_c = (c1 L11, c1 L1-1, c1 L10, c0 L00 + 2 c3 L20),
// cB_c = (c2 L2-2, c2 L2-1, c2 L21, c4 L22 - 3 c3 L20), cC = (-c4 L22 - 3 c3 L20 per channel, 0).
// Off the sphere it differs from Table 1 by exactly 3 c3 L20 (x^2 + y^2 + z^2 - 1) (Table1 minus
// this one).
SevenConstants PackUnitSphere10(const Sh9Rgb& sh);

// The polynomials of the two programs above, evaluated in double from the packed (float) registers;
// a reference for tests of the vertex program and of the packing.
glm::dvec3 EvaluateTable1(const SevenConstants& constants, glm::dvec3 n);
glm::dvec3 EvaluateUnitSphere10(const SevenConstants& constants, glm::dvec3 n);

}  // namespace vs11::irradiance
