// Dispatch of the row-sum kernels (irradiance/sh/row_sum_kernels.h) to the best Highway target the CPU
// supports; each target's kernels are compiled in its own irradiance/sh/row_sum_kernels_<target>.cc.

// Declare the per-target kernels once per Highway target.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "irradiance/sh/row_sum_kernels.cc"
#include "hwy/foreach_target.h"  // IWYU pragma: keep

#include "hwy/highway.h"
#include "irradiance/sh/row_sum_kernels.h"

namespace vs11::irradiance::kernels {
namespace HWY_NAMESPACE {
// Defined by irradiance/sh/row_sum_kernels_<target>.cc.
void AddClampedCosineSums(const CosineTable& table, const ChannelSums* normals, int count, ChannelSums* sums);
}  // namespace HWY_NAMESPACE
}  // namespace vs11::irradiance::kernels

#if HWY_ONCE
namespace vs11::irradiance::kernels {

// Every target Highway compiles for needs its irradiance/sh/row_sum_kernels_<target>.cc.
static_assert((HWY_TARGETS & ~(HWY_SCALAR | HWY_EMU128 | HWY_SSSE3 | HWY_SSE4 | HWY_AVX2 | HWY_AVX3)) == 0,
              "add an irradiance/sh/row_sum_kernels_<target>.cc for the new Highway target");
HWY_EXPORT(AddClampedCosineSums);

void AddClampedCosineSums(const CosineTable& table, const ChannelSums* normals, int count, ChannelSums* sums) {
  HWY_DYNAMIC_DISPATCH(AddClampedCosineSums)(table, normals, count, sums);
}

}  // namespace vs11::irradiance::kernels
#endif  // HWY_ONCE
