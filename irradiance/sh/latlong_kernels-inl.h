// The lat-long row sums (irradiance/sh/latlong_kernels.h) for one Highway target, the one HWY_TARGET
// names, included by exactly one irradiance/sh/latlong_kernels_<target>.cc; irradiance/sh/latlong_kernels.cc
// dispatches to them. One translation unit per target, as irradiance/sh/row_sum_kernels-inl.h.
//
// Each function is summed in its own pass over the row: the row (12 bytes per texel, 24 KB for a
// 2048-wide panorama) stays in the first-level cache for the passes after the first, and a pass
// holds only kLatLongPartialSums / lanes accumulators, which fit the registers of every target.

#ifndef HWY_TARGET
#error "define HWY_TARGET before including irradiance/sh/latlong_kernels-inl.h"
#endif

#include <algorithm>

#include "hwy/highway.h"
#include "irradiance/sh/latlong_kernels.h"

HWY_BEFORE_NAMESPACE();
namespace vs11::irradiance::kernels {
namespace HWY_NAMESPACE {
namespace {
namespace hn = hwy::HWY_NAMESPACE;

using DF = hn::CappedTag<float, kLatLongPartialSums>;
using VF = hn::Vec<DF>;
constexpr int kLanes = static_cast<int>(hn::MaxLanes(DF()));
constexpr int kVectors = kLatLongPartialSums / kLanes;
static_assert(kVectors * kLanes == kLatLongPartialSums, "a chunk is a whole number of vectors");

// Chunks of kLatLongPartialSums floats: `chunks` of them from `row` and `table`, into `partial`.
HWY_INLINE void AddChunks(const float* HWY_RESTRICT row, const float* HWY_RESTRICT table, int chunks,
                          double* HWY_RESTRICT partial) {
  const DF df;
  VF sums[kVectors];
  for (int run_start = 0; run_start < chunks; run_start += kLatLongFloatRun) {
    for (int v = 0; v < kVectors; ++v) sums[v] = hn::Zero(df);
    const int run_end = std::min(chunks, run_start + kLatLongFloatRun);
    for (int chunk = run_start; chunk < run_end; ++chunk) {
      const float* r = row + static_cast<std::size_t>(chunk) * kLatLongPartialSums;
      const float* t = table + static_cast<std::size_t>(chunk) * kLatLongPartialSums;
      for (int v = 0; v < kVectors; ++v) {
        sums[v] = hn::Add(sums[v], hn::Mul(hn::LoadU(df, r + v * kLanes), hn::LoadU(df, t + v * kLanes)));
      }
    }
    HWY_ALIGN float stored[kLatLongPartialSums];
    for (int v = 0; v < kVectors; ++v) hn::Store(sums[v], df, stored + v * kLanes);
    for (int p = 0; p < kLatLongPartialSums; ++p) partial[p] += stored[p];
  }
}

}  // namespace

LatLongRowSums SumLatLongRow(const float* row, const std::array<const float*, kLatLongColumnFunctions>& tables,
                             int floats) {
  const int whole = floats / kLatLongPartialSums;
  const int tail = floats - whole * kLatLongPartialSums;
  HWY_ALIGN float tail_row[kLatLongPartialSums] = {};
  HWY_ALIGN float tail_table[kLatLongPartialSums] = {};
  if (tail > 0) std::copy(row + whole * kLatLongPartialSums, row + floats, tail_row);
  LatLongRowSums result{};
  for (int j = 0; j < kLatLongColumnFunctions; ++j) {
    double partial[kLatLongPartialSums] = {};
    AddChunks(row, tables[j], whole, partial);
    if (tail > 0) {
      std::copy(tables[j] + whole * kLatLongPartialSums, tables[j] + floats, tail_table);
      AddChunks(tail_row, tail_table, 1, partial);
    }
    for (int p = 0; p < kLatLongPartialSums; ++p) result[j][p % 3] += partial[p];
  }
  return result;
}

}  // namespace HWY_NAMESPACE
}  // namespace vs11::irradiance::kernels
HWY_AFTER_NAMESPACE();
