// The row-sum kernels compiled for Highway's SCALAR target (see irradiance/sh/row_sum_kernels-inl.h).
#include "hwy/detect_targets.h"

#if HWY_TARGETS & HWY_SCALAR
#undef HWY_TARGET
#define HWY_TARGET HWY_SCALAR
#include "irradiance/sh/row_sum_kernels-inl.h"
#endif
