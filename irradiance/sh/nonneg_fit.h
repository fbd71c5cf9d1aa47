// A nine-term irradiance that never goes negative, fitted instead of windowed (`--window nonneg`).
//
// Per channel, the coefficients L' minimising the squared irradiance error over the sphere against
// the band-limited truth (the nine-term irradiance E of the given coefficients L),
//   integral (E' - E)^2 dn = sum_lm A_l^2 (L'_lm - L_lm)^2        (the y_lm are orthonormal),
// subject to E'(n) >= 0 at every direction of a dense set. In the irradiance coefficients
// u_lm = A_l L_lm this is the Euclidean projection of u onto a polyhedral cone: a small quadratic
// program with nine unknowns and as many linear inequalities as directions. NLopt's SLSQP solves it
// (its quasi-Newton matrix starts as the identity, the objective's exact Hessian up to a factor, so
// its first quadratic subproblem is already the whole problem). Only a few constraints are active
// at the optimum, so the fit is an exchange method: each round adds the lowest negative directions
// of the current fit and the local minima of E' on the sphere below them (found by descent), until
// none is negative (a few dozen constraints instead of a thousand: SLSQP's cost grows with their
// number); what
// the solver's tolerance leaves below zero (about 1e-7 of the peak) is then lifted by raising the
// constant term.
//
// Unlike the windows, which scale whole bands, this moves each coefficient on its own: a small
// light keeps its peak and only the far side is lifted to zero, so its max error stays close to that
// of the unwindowed terms where dering (one lambda for all bands) blurs the peak away.
#pragma once

#include <array>
#include <span>

#include <glm/glm.hpp>

#include "irradiance/sh/sh9.h"

namespace vs11::irradiance {

// Directions of the first round (SphereNormals), and the most rounds of added minima.
inline constexpr int kNonNegativeFitNormals = 1000;
inline constexpr int kNonNegativeFitMaxRounds = 40;
// E' >= kNonNegativeMargin x (largest |E| at the directions) at the constraints, so that rounding
// does not leave -1e-16 crumbs where the fit touches zero.
inline constexpr double kNonNegativeMargin = 1e-9;

struct NonNegativeFit {
  Sh9Rgb coefficients;
  std::array<int, 3> rounds{};       // solves per channel (0: the input was already non-negative)
  std::array<int, 3> constraints{};  // directions constrained in the last solve, per channel
  std::array<double, 3> lift{};      // irradiance added everywhere after the solve (its residue below 0)
  bool solver_ok = true;             // NLopt reported success (or the input needed no fit) every time
};

// The fit for each channel of `sh`; channels already non-negative at `normals` and at the minima
// are returned unchanged. `normals` unit vectors: where each round looks for negative irradiance
// (and starts its descents).
NonNegativeFit FitNonNegative(const Sh9Rgb& sh, std::span<const glm::dvec3> normals);

// One solve of the quadratic program per channel with E' >= 0 exactly at `directions` (no margin,
// no added minima): every channel is fitted, even one already non-negative there (which the fit
// then leaves where it is). For tests against a brute-force solution.
Sh9Rgb FitNonNegativeAt(const Sh9Rgb& sh, std::span<const glm::dvec3> directions);

// The same with SphereNormals(kNonNegativeFitNormals).
Sh9Rgb FitNonNegative(const Sh9Rgb& sh);

// The lowest irradiance of one channel of `sh` over the unit sphere, found by descent along the
// sphere from each of the `starts` lowest of `normals` (the quadratic has at most a few local
// minima). Returns the direction.
glm::dvec3 LowestDirection(const Sh9Rgb& sh, int channel, std::span<const glm::dvec3> normals, int starts = 6);

}  // namespace vs11::irradiance
