// The batch engine's kernels compiled for Highway's SSSE3 target (see vm/engines/batch_kernels-inl.h).
#include "hwy/detect_targets.h"

#if HWY_TARGETS & HWY_SSSE3
#undef HWY_TARGET
#define HWY_TARGET HWY_SSSE3
#include "vm/engines/batch_kernels-inl.h"
#endif
