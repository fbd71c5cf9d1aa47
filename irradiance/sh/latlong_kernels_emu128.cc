// The lat-long row sums compiled for Highway's EMU128 target (see irradiance/sh/latlong_kernels-inl.h).
#include "hwy/detect_targets.h"

#if HWY_TARGETS & HWY_EMU128
#undef HWY_TARGET
#define HWY_TARGET HWY_EMU128
#include "irradiance/sh/latlong_kernels-inl.h"
#endif
