// The row-sum kernels compiled for Highway's EMU128 target (see irradiance/sh/row_sum_kernels-inl.h).
#include "hwy/detect_targets.h"

#if HWY_TARGETS & HWY_EMU128
#undef HWY_TARGET
#define HWY_TARGET HWY_EMU128
#include "irradiance/sh/row_sum_kernels-inl.h"
#endif
