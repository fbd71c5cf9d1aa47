// The row-sum kernels compiled for Highway's SSE4 target (see irradiance/sh/row_sum_kernels-inl.h).
#include "hwy/detect_targets.h"

#if HWY_TARGETS & HWY_SSE4
#undef HWY_TARGET
#define HWY_TARGET HWY_SSE4
#include "irradiance/sh/row_sum_kernels-inl.h"
#endif
