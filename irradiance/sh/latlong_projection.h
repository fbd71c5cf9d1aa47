// Projection of a lat-long panorama (the kLatLong layout of irradiance/io/environment_io.h) onto the
// nine SH coefficients where it lies, without resampling it to a cube first:
//
//   L_lm = sum over every pixel of radiance x y_lm(pixel centre direction) x exact pixel solid angle,
//
// the pixel's solid angle being dphi (cos theta_top - cos theta_bottom). The basis is separable on
// the panorama's grid (direction = (sin phi sin theta, cos theta, cos phi sin theta)), so a row's
// contribution is five sums over its pixels, radiance times a column table (1, cos phi, sin phi,
// cos 2 phi, sin 2 phi, times the column's azimuth width), combined in double with six row factors
// (1, cos theta, sin theta, sin theta cos theta, sin^2 theta, cos^2 theta, times the row's
// cos theta_top - cos theta_bottom). Cost: one pass over the pixels as they lie in memory, 15 float
// multiply-adds per pixel (irradiance/sh/latlong_kernels.h); the tables are O(W + H).
//
// Coarser levels (the paper's mip acceleration, in the panorama's own layout): level k of a
// pyramid for a cube face size N is the panorama averaged down to 4 (N >> k) x 2 (N >> k) pixels,
// the grid of a cube of face N >> k (a cube face spans 90 degrees of azimuth), each coarse pixel the
// solid-angle-weighted mean of the fine pixels it covers (fractions of pixels at its edges where the
// sizes do not divide), and its basis weight the exact sum of the finest pixels' y_lm x solid angle
// over it, so a coarse level differs from level 0 only by treating the radiance as constant over
// each coarse pixel, as the cube's mip levels do (irradiance/sh/sh_projection.h). Level 0 is the
// panorama at its own resolution; a level whose grid would not be coarser than the level above it is
// that level again (a panorama has no more detail to give).
#pragma once

#include <array>
#include <vector>

#include "irradiance/io/cube_map.h"
#include "irradiance/sh/latlong_kernels.h"
#include "irradiance/sh/sh9.h"

namespace vs11::irradiance {

inline constexpr int kLatLongRowFunctions = 6;

// The basis of one level summed over each pixel's finest pixels, separably.
struct LatLongTables {
  // Column j's sum over its finest columns of f_j(phi) dphi, in double, and the same rounded to
  // float once with each value three times (once per channel: the interleaved layout of a row).
  std::array<std::vector<double>, kernels::kLatLongColumnFunctions> column_sums;
  std::array<std::vector<float>, kernels::kLatLongColumnFunctions> columns;
  // Row i's sum over its finest rows of g_i(theta) (cos theta_top - cos theta_bottom), in double.
  std::array<std::vector<double>, kLatLongRowFunctions> rows;
};

// The tables of a panorama's own pixels (level 0) for width x width / 2 (width even, > 0).
LatLongTables FinestLatLongTables(int width);

struct LatLongLevel {
  Image image;  // width == 2 height; mean radiance per pixel
  LatLongTables tables;
};

// The level of a panorama itself (level 0), taking `latlong` (width == 2 height > 0, asserted).
LatLongLevel MakeLatLongLevel(Image latlong);

// `from` averaged down to `width` x width / 2 pixels (width even, 2 <= width < from's width,
// asserted), as described above. The rows are shared among up to `threads` threads of
// ThreadPool::Default(), with the same result for any count.
LatLongLevel ReduceLatLongLevel(const LatLongLevel& from, int width, int threads = 1);

// The nine coefficients of one level. Precision: every product radiance x column weight is formed
// in float and summed in float over at most 16 products per partial sum, then in double; the
// result is within 1e-6 of the largest coefficient of a double projection of the same pixels. Rows
// are summed on up to `threads` threads; the result is the same bits for any thread count and any
// SIMD target. Finite radiance gives finite coefficients: a row whose float sums overflow (pixels
// above about FLT_MAX / 64) is summed again with its weights scaled down by a power of two, exactly.
Sh9Rgb ProjectLatLongLevel(const Image& image, const LatLongTables& tables, int threads = 1);
inline Sh9Rgb ProjectLatLongLevel(const LatLongLevel& level, int threads = 1) {
  return ProjectLatLongLevel(level.image, level.tables, threads);
}

// The exact projection of a panorama at its own resolution (width == 2 height > 0, asserted).
Sh9Rgb ProjectLatLong(const Image& latlong, int threads = 1);

// Every level for a cube face size `face_size` (a power of two, asserted): LevelCount(face_size)
// levels, levels[k] indexing `distinct`, whose first element is the panorama itself.
struct LatLongPyramid {
  int face_size = 0;
  std::vector<LatLongLevel> distinct;
  std::vector<int> levels;

  const LatLongLevel& level(int k) const { return distinct[static_cast<std::size_t>(levels[static_cast<std::size_t>(k)])]; }
};

// Takes `latlong` as level 0; each coarser level is reduced from the one above it (by halves, but
// for the first reduction from the panorama's own size).
LatLongPyramid BuildLatLongPyramid(Image latlong, int face_size, int threads = 1);

}  // namespace vs11::irradiance
