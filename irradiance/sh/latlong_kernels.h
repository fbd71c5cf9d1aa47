// Row sums of a lat-long panorama's projection (irradiance/sh/latlong_projection.h). Compiled for every
// Highway target, each in its own irradiance/sh/latlong_kernels_<target>.cc (as the row-sum kernels,
// irradiance/sh/row_sum_kernels-inl.h), and dispatched at run time to the best target the CPU has.
//
// A row of the panorama is read as it lies in memory, 3 W interleaved floats (r g b r g b ...), and
// multiplied by a table of the same length holding each column's weight three times, so no
// deinterleaving is needed: the channel of float i is i % 3.
//
// Every target gives the same bits. Float i of a row goes to partial sum i % kLatLongPartialSums
// (a multiple of 3 and of every target's vector width, so each partial sum holds one channel); a
// partial sum adds at most kLatLongFloatRun products in float, in order of i, before it is added
// into its double partial sum; the double partial sums of a channel are then added in order of
// their index, from +0. Products and sums are separate operations (never fused; the build has
// -ffp-contract=off). A row's tail is padded with +0.
#pragma once

#include <array>
#include <cstddef>

namespace vs11::irradiance::kernels {

inline constexpr int kLatLongPartialSums = 48;
inline constexpr int kLatLongFloatRun = 16;
// The column functions a row is summed against (see latlong_projection.cc: 1, cos phi, sin phi,
// cos 2 phi, sin 2 phi, each times the column's share of the texel's solid angle).
inline constexpr int kLatLongColumnFunctions = 5;

// For each function j, each channel c: sum over the row's floats i with i % 3 == c of
// row[i] * tables[j][i].
using LatLongRowSums = std::array<std::array<double, 3>, kLatLongColumnFunctions>;

// `row` and each of `tables` hold `floats` floats (3 x the row's width).
LatLongRowSums SumLatLongRow(const float* row, const std::array<const float*, kLatLongColumnFunctions>& tables,
                             int floats);

}  // namespace vs11::irradiance::kernels
