// The row-sum kernels compiled for Highway's AVX3 target (see irradiance/sh/row_sum_kernels-inl.h).
#include "hwy/detect_targets.h"

#if HWY_TARGETS & HWY_AVX3
#undef HWY_TARGET
#define HWY_TARGET HWY_AVX3
#include "irradiance/sh/row_sum_kernels-inl.h"
#endif
