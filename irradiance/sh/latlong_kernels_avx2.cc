// The lat-long row sums compiled for Highway's AVX2 target (see irradiance/sh/latlong_kernels-inl.h).
#include "hwy/detect_targets.h"

#if HWY_TARGETS & HWY_AVX2
#undef HWY_TARGET
#define HWY_TARGET HWY_AVX2
#include "irradiance/sh/latlong_kernels-inl.h"
#endif
