// The row-sum kernels (irradiance/sh/row_sum_kernels.h) for one Highway target, the one HWY_TARGET
// names, included by exactly one irradiance/sh/row_sum_kernels_<target>.cc; irradiance/sh/row_sum_kernels.cc
// dispatches to them with HWY_EXPORT / HWY_DYNAMIC_DISPATCH. One translation unit per target, as the
// batch engine's kernels (vm/engines/batch_kernels-inl.h gives the reason there), so the libraries
// compile their per-target kernels one way.
//
// Bit exactness: each target holds the kRowSumLanes partial sums in kGroups vectors of its width and
// adds the terms with separate multiplies and adds (never MulAdd; the build has -ffp-contract=off,
// so none is fused), and the partial sums are folded in lane order outside the vectors.

#ifndef HWY_TARGET
#error "define HWY_TARGET before including irradiance/sh/row_sum_kernels-inl.h"
#endif

#include <algorithm>
#include <cstddef>

#include "hwy/highway.h"
#include "irradiance/sh/row_sum_kernels.h"

HWY_BEFORE_NAMESPACE();
namespace vs11::irradiance::kernels {
namespace HWY_NAMESPACE {
namespace {
namespace hn = hwy::HWY_NAMESPACE;

// Up to kRowSumLanes doubles per vector: 8 with AVX-512, 4 with AVX2, 2 with SSE and EMU128, 1 scalar.
using DD = hn::CappedTag<double, kRowSumLanes>;
using VD = hn::Vec<DD>;
constexpr int kLanesPerVector = static_cast<int>(hn::MaxLanes(DD()));
constexpr int kGroups = kRowSumLanes / kLanesPerVector;
static_assert(kGroups * kLanesPerVector == kRowSumLanes, "a vector holds a whole number of partial sums");

// The kRowSumLanes partial sums of each channel, kLanesPerVector per vector.
struct PartialSums {
  VD red[kGroups];
  VD green[kGroups];
  VD blue[kGroups];
};

HWY_INLINE void Clear(PartialSums& sums) {
  for (int k = 0; k < kGroups; ++k) sums.red[k] = sums.green[k] = sums.blue[k] = hn::Zero(DD());
}

// Partial sum j to kRowSumLanes - 1 in order, from +0.
HWY_INLINE ChannelSums Fold(const PartialSums& sums) {
  const DD dd;
  HWY_ALIGN double red[kRowSumLanes], green[kRowSumLanes], blue[kRowSumLanes];
  for (int k = 0; k < kGroups; ++k) {
    hn::Store(sums.red[k], dd, red + k * kLanesPerVector);
    hn::Store(sums.green[k], dd, green + k * kLanesPerVector);
    hn::Store(sums.blue[k], dd, blue + k * kLanesPerVector);
  }
  ChannelSums total{0.0, 0.0, 0.0};
  for (int j = 0; j < kRowSumLanes; ++j) {
    total[0] += red[j];
    total[1] += green[j];
    total[2] += blue[j];
  }
  return total;
}

HWY_INLINE void AddProducts(VD factor, const double* HWY_RESTRICT red, const double* HWY_RESTRICT green,
                            const double* HWY_RESTRICT blue, int k, PartialSums& sums) {
  const DD dd;
  const int offset = k * kLanesPerVector;
  sums.red[k] = hn::Add(sums.red[k], hn::Mul(factor, hn::LoadU(dd, red + offset)));
  sums.green[k] = hn::Add(sums.green[k], hn::Mul(factor, hn::LoadU(dd, green + offset)));
  sums.blue[k] = hn::Add(sums.blue[k], hn::Mul(factor, hn::LoadU(dd, blue + offset)));
}

// The columns of a CosineTable, from one texel on.
struct CosineColumns {
  const double* wx;
  const double* wy;
  const double* wz;
  const double* r;
  const double* g;
  const double* b;
};

HWY_INLINE CosineColumns ColumnsAt(const CosineTable& table, std::size_t offset) {
  return {table.wx + offset,           table.wy + offset,           table.wz + offset,
          table.radiance.red + offset, table.radiance.green + offset, table.radiance.blue + offset};
}

// Texels x .. x + kRowSumLanes - 1 of a cosine row (all of them present).
HWY_INLINE void AddCosineTexels(const CosineColumns& c, VD nx, VD ny, VD nz, PartialSums& sums) {
  const DD dd;
  const VD zero = hn::Zero(dd);
  for (int k = 0; k < kGroups; ++k) {
    const int offset = k * kLanesPerVector;
    const VD dot = hn::Add(hn::Add(hn::Mul(nx, hn::LoadU(dd, c.wx + offset)), hn::Mul(ny, hn::LoadU(dd, c.wy + offset))),
                           hn::Mul(nz, hn::LoadU(dd, c.wz + offset)));
    // max(0, dot) with NaN and -0 giving +0.
    const VD cosine = hn::IfThenElse(hn::Gt(dot, zero), dot, zero);
    AddProducts(cosine, c.r, c.g, c.b, k, sums);
  }
}

ChannelSums CosineRowSum(const CosineTable& table, int row, const ChannelSums& normal) {
  const DD dd;
  const VD nx = hn::Set(dd, normal[0]), ny = hn::Set(dd, normal[1]), nz = hn::Set(dd, normal[2]);
  const int n = table.row_size;
  const std::size_t base = static_cast<std::size_t>(row) * n;
  PartialSums sums;
  Clear(sums);
  int x = 0;
  for (; x + kRowSumLanes <= n; x += kRowSumLanes) AddCosineTexels(ColumnsAt(table, base + x), nx, ny, nz, sums);
  if (x < n) {
    // Zero weights: a cosine of +0 times a radiance of +0.
    HWY_ALIGN double tail[6][kRowSumLanes] = {};
    const CosineColumns from = ColumnsAt(table, base + x);
    const double* columns[6] = {from.wx, from.wy, from.wz, from.r, from.g, from.b};
    for (int i = 0; i < 6; ++i) std::copy(columns[i], columns[i] + (n - x), tail[i]);
    AddCosineTexels({tail[0], tail[1], tail[2], tail[3], tail[4], tail[5]}, nx, ny, nz, sums);
  }
  return Fold(sums);
}

HWY_INLINE void AddTo(ChannelSums& sum, const ChannelSums& term) {
  for (int c = 0; c < 3; ++c) sum[c] += term[c];
}

}  // namespace

void AddClampedCosineSums(const CosineTable& table, const ChannelSums* normals, int count, ChannelSums* sums) {
  for (int row = 0; row < table.rows; ++row) {
    for (int k = 0; k < count; ++k) AddTo(sums[k], CosineRowSum(table, row, normals[k]));
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace vs11::irradiance::kernels
HWY_AFTER_NAMESPACE();
