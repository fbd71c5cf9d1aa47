// --engine gl in the irrmap job: the chosen level's frame on the GPU through IrrmapOptions::gpu_frame
// (irradiance/jobs/gpu_frame_hook.h), whose coefficients, constants and irradiance map then stand for
// the CPU's in the report and the files.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "irradiance/jobs/gpu_frame_hook.h"
#include "irradiance/jobs/irrmap_environment.h"
#include "irradiance/jobs/irrmap_job.h"
#include "vm/core/result.h"

namespace vs11::irradiance {

// What the frame runs on: the job's environment (a cube's mips and basis pyramid; a panorama's
// projection stays on the CPU), its window, the chosen order's program and the irradiance map's face
// size (0 with coefficients_only: no map).
struct IrrmapGpuFrame {
  const GpuFrameHook& hook;
  const IrrmapEnvironment& environment;
  ShWindow window = ShWindow::kNone;
  const PaperProgram& program;
  int map_size = 0;
};

// Fills report.gpu. Where WhyNotOnGpu gives a reason, only that (and a warning): the projection stays
// on the CPU and `irradiance` empty. Otherwise runs the frame and replaces report.coefficients,
// constants and program_constants with the GPU's, with the "gpu_frame" timing, and `irradiance` with
// the program's outputs per texel of the map (CubeTexelDirections(map_size)). The hook's error (its
// code, the message prefixed "--engine gl: "), where it fails.
Status RunIrrmapGpuFrame(const IrrmapGpuFrame& frame, IrrmapReport& report, std::vector<glm::dvec3>& irradiance);

}  // namespace vs11::irradiance
