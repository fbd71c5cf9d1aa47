// The batch engine's kernels compiled for Highway's SSE4 target (see vm/engines/batch_kernels-inl.h).
#include "hwy/detect_targets.h"

#if HWY_TARGETS & HWY_SSE4
#undef HWY_TARGET
#define HWY_TARGET HWY_SSE4
#include "vm/engines/batch_kernels-inl.h"
#endif
