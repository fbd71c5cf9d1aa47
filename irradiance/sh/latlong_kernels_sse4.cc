// The lat-long row sums compiled for Highway's SSE4 target (see irradiance/sh/latlong_kernels-inl.h).
#include "hwy/detect_targets.h"

#if HWY_TARGETS & HWY_SSE4
#undef HWY_TARGET
#define HWY_TARGET HWY_SSE4
#include "irradiance/sh/latlong_kernels-inl.h"
#endif
