// Double-precision row sums of the brute-force ground truth (irradiance/sh/ground_truth.cc). Compiled for every
// Highway target, each in its own irradiance/sh/row_sum_kernels_<target>.cc (see
// irradiance/sh/row_sum_kernels-inl.h for why), and dispatched at run time to the best target the CPU
// has; the tests run them on every target the CPU supports (hwy::SetSupportedTargetsForTest).
//
// Every target gives the same bits. A row is summed in kRowSumLanes partial sums: partial sum j adds
// the terms of texels x with x % kRowSumLanes == j, in order of x, and the partial sums are then
// added in order j = 0 .. kRowSumLanes - 1, starting from +0. A target's vectors hold 1, 2, 4 or 8 of
// the partial sums, so the additions, not only their result, are the same on all of them. A row's
// tail is padded with texels whose terms are +0, which changes no sum.
#pragma once

#include <array>

namespace vs11::irradiance::kernels {

inline constexpr int kRowSumLanes = 8;

// One sum per channel: red, green, blue.
using ChannelSums = std::array<double, 3>;

// A row of radiance as three channel arrays of doubles.
struct RadianceRow {
  const double* red;
  const double* green;
  const double* blue;
};

// Rows of texels as structure-of-arrays doubles: texel x of row y is element y * row_size + x of each
// array. (wx, wy, wz) is the texel's direction times its solid angle.
struct CosineTable {
  const double* wx;
  const double* wy;
  const double* wz;
  RadianceRow radiance;
  int row_size;
  int rows;
};

// For each normal k < count, and each row of `table` in order: sums[k] += the sum over the row of
// radiance * max(0, normal . w), per channel (a NaN cosine counts as 0). The dot product is
// (nx wx + ny wy) + nz wz.
void AddClampedCosineSums(const CosineTable& table, const ChannelSums* normals, int count, ChannelSums* sums);

}  // namespace vs11::irradiance::kernels
