// The batch engine's kernels compiled for Highway's SCALAR target (see vm/engines/batch_kernels-inl.h).
#include "hwy/detect_targets.h"

#if HWY_TARGETS & HWY_SCALAR
#undef HWY_TARGET
#define HWY_TARGET HWY_SCALAR
#include "vm/engines/batch_kernels-inl.h"
#endif
