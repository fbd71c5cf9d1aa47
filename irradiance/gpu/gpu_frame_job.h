// irrmap's GPU frame (irradiance/jobs/gpu_frame_hook.h) on GpuFrame and ProgramStage: what
// `irrmap --engine gl` sets as IrrmapOptions::gpu_frame.
#pragma once

#include <optional>

#include "irradiance/jobs/gpu_frame_hook.h"

namespace vs11::irradiance::gpu {

// A hook that, per call, makes a context on `device` (vm/gl's index; nullopt: Mesa's llvmpipe),
// uploads the environment, builds its mips, projects the level, packs the constants and runs the
// program over the normals, all on the GPU, and reads back the coefficients, the constants and the
// program's outputs once at the end.
GpuFrameHook MakeGpuFrameHook(std::optional<int> device);

}  // namespace vs11::irradiance::gpu
