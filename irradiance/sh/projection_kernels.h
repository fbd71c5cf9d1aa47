// SIMD kernels of the SH projection (irradiance/sh/sh_projection.cc), compiled for every Highway target
// in irradiance/sh/projection_kernels.cc and dispatched at run time to the best one the CPU has (the
// tests run them on every target the CPU supports, hwy::SetSupportedTargetsForTest).
#pragma once

#include <array>

namespace vs11::irradiance::kernels {

// Per-texel weights of a face (each size * size floats, row-major, the same on all six faces): the
// texel's exact solid angle q (TexelSolidAngle), q r and q r^2, with r = 1 / sqrt(1 + s^2 + t^2)
// and (s, t) its centre's face coordinates. Formed in double, rounded to float once.
struct FaceWeights {
  const float* q;
  const float* qr;
  const float* qr2;
};

// For a face row of texels with radiance L, the sums over the row of
//
//   moment   0       1          2            3           4
//   sum of   L q     L q r      L q r s      L q r^2     L q r^2 s
//
// per channel (L q r^2 s^2 is not summed: it is L q - (1 + t^2) L q r^2). Every SH9 basis function
// times q is a combination of these whose factors depend on the face and on t only (the unit
// direction is r times a face-dependent linear form in 1, s and t, and the factors are polynomials
// of degree <= 2 in t), so a face's nine coefficients follow from its 15 row moments summed over
// rows with weights 1, t and t^2, and no basis is read from memory.
inline constexpr int kMomentSums = 5 * 3;                                  // [moment * 3 + channel]
using FaceMomentSums = std::array<std::array<double, kMomentSums>, 3>;  // [power of t]
using CubeMomentSums = std::array<FaceMomentSums, 6>;                     // [face]
using CubeTexels = std::array<const float*, 6>;  // each face: size * size interleaved rgb texels

// The moments of the six faces of a cube of `size`. Each term is formed in float, summed in float
// lanes over at most 16 vectors of a row (16 terms per lane) and from there on in double (the stability report's float
// sums fail at 2048^2; blocks this short do not), so results differ between targets only by the
// float rounding of the terms and the order of the double sums.
void CubeMoments(const CubeTexels& faces, const FaceWeights& weights, int size, CubeMomentSums& out);

// One row of a 2 x 2 box-filtered mip level: out[x] = ((a + b) + (c + d)) * 0.25 per channel, where
// a, b are texels 2x, 2x + 1 of `upper` and c, d of `lower` (interleaved rgb rows of 2 * out_width
// texels). The order of the additions is fixed, so every target gives the same bits.
void HalveRowPair(const float* upper, const float* lower, float* out, int out_width);

}  // namespace vs11::irradiance::kernels
