// The row-sum kernels compiled for Highway's AVX2 target (see irradiance/sh/row_sum_kernels-inl.h).
#include "hwy/detect_targets.h"

#if HWY_TARGETS & HWY_AVX2
#undef HWY_TARGET
#define HWY_TARGET HWY_AVX2
#include "irradiance/sh/row_sum_kernels-inl.h"
#endif
