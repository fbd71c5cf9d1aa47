// The lat-long row sums compiled for Highway's SSSE3 target (see irradiance/sh/latlong_kernels-inl.h).
#include "hwy/detect_targets.h"

#if HWY_TARGETS & HWY_SSSE3
#undef HWY_TARGET
#define HWY_TARGET HWY_SSSE3
#include "irradiance/sh/latlong_kernels-inl.h"
#endif
