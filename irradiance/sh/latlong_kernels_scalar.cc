// The lat-long row sums compiled for Highway's SCALAR target (see irradiance/sh/latlong_kernels-inl.h).
#include "hwy/detect_targets.h"

#if HWY_TARGETS & HWY_SCALAR
#undef HWY_TARGET
#define HWY_TARGET HWY_SCALAR
#include "irradiance/sh/latlong_kernels-inl.h"
#endif
