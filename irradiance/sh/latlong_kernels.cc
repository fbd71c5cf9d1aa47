// Dispatch of the lat-long row sums (irradiance/sh/latlong_kernels.h) to the best Highway target the
// CPU supports; each target's kernel is compiled in its own irradiance/sh/latlong_kernels_<target>.cc.

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "irradiance/sh/latlong_kernels.cc"
#include "hwy/foreach_target.h"  // IWYU pragma: keep

#include "hwy/highway.h"
#include "irradiance/sh/latlong_kernels.h"

namespace vs11::irradiance::kernels {
namespace HWY_NAMESPACE {
// Defined by irradiance/sh/latlong_kernels_<target>.cc.
LatLongRowSums SumLatLongRow(const float* row, const std::array<const float*, kLatLongColumnFunctions>& tables,
                             int floats);
}  // namespace HWY_NAMESPACE
}  // namespace vs11::irradiance::kernels

#if HWY_ONCE
namespace vs11::irradiance::kernels {

static_assert((HWY_TARGETS & ~(HWY_SCALAR | HWY_EMU128 | HWY_SSSE3 | HWY_SSE4 | HWY_AVX2 | HWY_AVX3)) == 0,
              "add an irradiance/sh/latlong_kernels_<target>.cc for the new Highway target");
HWY_EXPORT(SumLatLongRow);

LatLongRowSums SumLatLongRow(const float* row, const std::array<const float*, kLatLongColumnFunctions>& tables,
                             int floats) {
  return HWY_DYNAMIC_DISPATCH(SumLatLongRow)(row, tables, floats);
}

}  // namespace vs11::irradiance::kernels
#endif  // HWY_ONCE
