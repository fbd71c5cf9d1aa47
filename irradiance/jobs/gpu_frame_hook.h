// How the irrmap job reaches a GPU frame (irradiance/gpu/gpu_frame_job.h) without linking a GPU API:
// the tool sets IrrmapOptions::gpu_frame for --engine gl, and the job hands it the chosen level's
// work. The library itself needs no EGL.
#pragma once

#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "irradiance/io/cube_map.h"
#include "irradiance/report/paper_program.h"
#include "irradiance/sh/sh9.h"
#include "irradiance/sh/sh_order.h"
#include "irradiance/sh/sh_projection.h"
#include "vm/core/result.h"

namespace vs11::irradiance {

// One frame: the environment (level 0) and its basis pyramid, the level to project, the paper's
// program and the normals to run it over (none: no program stage).
struct GpuFrameRequest {
  const CubeMap& environment;
  const BasisPyramid& basis;
  int level = 0;
  const PaperProgram& program;
  std::span<const glm::dvec3> normals;
};

struct GpuFrameResult {
  std::string renderer;             // GL_RENDERER
  std::vector<std::string> stages;  // what ran on the GPU, in order ("upload", "env_mips", ...)
  Sh9Rgb coefficients;              // as the GPU summed them (floats)
  SevenConstants constants;         // Table 1, packed on the GPU
  std::vector<glm::dvec3> irradiance;  // the program's output rgb per normal
  double error_factor = 0.0;        // its bound against the CPU projection (GpuProjectionErrorFactor)
};

// Fills `result`, or returns why the frame could not run.
using GpuFrameHook = std::function<Status(const GpuFrameRequest&, GpuFrameResult&)>;

// coeffs.json's "gpu": what ran where, and how far the GPU's coefficients are from the CPU's.
struct GpuFrameReport {
  std::string renderer;
  std::vector<std::string> stages;  // on the GPU; the others ran on the CPU
  std::string cpu_reason;           // why the projection stayed on the CPU, when it did
  // max |GPU - CPU| over the 27 coefficients, divided by the largest |CPU| coefficient.
  double max_coefficient_difference = 0.0;
  double ms = 0.0;  // the whole GPU frame, reads included
};

// Why a job's frame cannot run on the GPU (its projection stays on the CPU, and only the program
// runs on the gl engine), or nullopt: a cube environment, the paper's program and no window.
std::optional<std::string> WhyNotOnGpu(bool cube, ShOrder order, ShWindow window);

// max |gpu - cpu| over the 27 coefficients over the largest |cpu| (the difference itself when all are 0).
double MaxCoefficientDifference(const Sh9Rgb& gpu, const Sh9Rgb& cpu);

// {"renderer", "stages", "cpu_reason" (when set), "max_coefficient_difference", "ms"}.
nlohmann::ordered_json GpuFrameJson(const GpuFrameReport& gpu);

}  // namespace vs11::irradiance
