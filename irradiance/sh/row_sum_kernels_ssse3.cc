// The row-sum kernels compiled for Highway's SSSE3 target (see irradiance/sh/row_sum_kernels-inl.h).
#include "hwy/detect_targets.h"

#if HWY_TARGETS & HWY_SSSE3
#undef HWY_TARGET
#define HWY_TARGET HWY_SSSE3
#include "irradiance/sh/row_sum_kernels-inl.h"
#endif
