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

// The powers of r and of s in each of the five moments above (moment 2 is L q r^1 s^1).
inline constexpr std::array<int, 5> kMomentPowerOfR = {0, 1, 1, 2, 2};
inline constexpr std::array<int, 5> kMomentPowerOfS = {0, 0, 1, 0, 1};

// A coarse mip level's texel is a block of finest texels over which t varies, so a row's sums cannot
// be weighted by t afterwards as the finest level's are: the powers of t go into the weights
// instead. A block's weights are the sums over its finest children of the nine products below, each
// one moment (0-4 above) times a power of t, and a face's coefficients follow from its nine sums of
// L x weight exactly as from the finest level's moments (FaceMomentSums[power][moment * 3 + channel];
// L q r^2 s^2 again is L q - L q r^2 - L q r^2 t^2, and the other six slots are zero). These are all
// that the nine SH9 basis functions times q need, so a block's weights are exactly the nine summed
// basis weights of the block (in another basis), whatever its size.
inline constexpr int kBlockMoments = 9;
struct BlockMomentSlot {
  int power_of_t;
  int moment;
};
inline constexpr std::array<BlockMomentSlot, kBlockMoments> kBlockMomentSlots = {{
    {0, 0},  // q
    {0, 1},  // q r
    {0, 2},  // q r s
    {1, 1},  // q r t
    {0, 3},  // q r^2
    {0, 4},  // q r^2 s
    {1, 3},  // q r^2 t
    {1, 4},  // q r^2 s t
    {2, 3},  // q r^2 t^2
}};

// The weights of a coarse level: kBlockMoments arrays of size * size floats (row-major, the same on
// all six faces), in kBlockMomentSlots order.
using BlockWeights = std::array<const float*, kBlockMoments>;

// The sums of L x weight over every texel of each of the six faces of a coarse level of `size`,
// placed in the slots kBlockMomentSlots names (the others are zero). Terms are formed and summed in
// float exactly as CubeMoments does (at most 16 terms per lane, then double), over the face's texels
// in memory order: the weights already hold t, so rows need no separate treatment.
void CubeBlockMoments(const CubeTexels& faces, const BlockWeights& weights, int size, CubeMomentSums& out);

// One row of a 2 x 2 box-filtered mip level: out[x] = (a/4 + b/4) + (c/4 + d/4) per channel, where
// a, b are texels 2x, 2x + 1 of `upper` and c, d of `lower` (interleaved rgb rows of 2 * out_width
// texels). The order of the additions is fixed, so every target gives the same bits. Quartering
// first keeps every sum within float range for any finite texels (((a + b) + (c + d)) / 4 overflows
// above FLT_MAX / 4) and gives the same bits as that wherever it does not overflow, except for
// texels under 2^-124, whose quarters lose bits as subnormals.
void HalveRowPair(const float* upper, const float* lower, float* out, int out_width);

// HalveRowPair, also copying the two rows (2 * out_width texels each) to `copy_upper` and
// `copy_lower` from the loads the halving makes: one pass over the rows for a pyramid's refill.
void CopyAndHalveRowPair(const float* upper, const float* lower, float* copy_upper, float* copy_lower, float* out,
                         int out_width);

}  // namespace vs11::irradiance::kernels
