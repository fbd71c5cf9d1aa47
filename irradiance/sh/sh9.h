// The irradiance library's SH work on top of the nine-coefficient core (vm/reference/sh9.h): band
// norms and the windows against ringing.
#pragma once

#include <array>
#include <optional>
#include <span>
#include <string_view>

#include <glm/glm.hpp>

#include "vm/core/name_table.h"
#include "vm/reference/sh9.h"

namespace vs11::irradiance {

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

}  // namespace vs11::irradiance
