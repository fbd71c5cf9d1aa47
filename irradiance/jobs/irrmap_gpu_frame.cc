#include "irradiance/jobs/irrmap_gpu_frame.h"

#include <chrono>
#include <utility>

#include <fmt/format.h>

#include "irradiance/io/cube_map.h"

namespace vs11::irradiance {

Status RunIrrmapGpuFrame(const IrrmapGpuFrame& frame, IrrmapReport& report, std::vector<glm::dvec3>& irradiance) {
  GpuFrameReport& gpu = report.gpu.emplace();
  const IrrmapEnvironment& environment = frame.environment;
  if (std::optional<std::string> reason = WhyNotOnGpu(environment.mips.has_value(), report.order, frame.window)) {
    gpu.stages = {"program"};
    gpu.cpu_reason = *reason;
    report.warnings.push_back(fmt::format("--engine gl: {}; the projection ran on the CPU", *reason));
    return {};
  }
  // Only now: a frame that stays on the CPU needs no directions here.
  const std::vector<glm::dvec3> normals = frame.map_size > 0 ? CubeTexelDirections(frame.map_size)
                                                             : std::vector<glm::dvec3>{};
  GpuFrameResult result;
  const auto start = std::chrono::steady_clock::now();
  if (const Status ran =
          frame.hook({environment.mips->levels[0], *environment.basis, report.level, frame.program, normals}, result);
      !ran) {
    return Failure(ran.error().code, fmt::format("--engine gl: {}", ran.message()));
  }
  gpu.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  report.timings.push_back({"gpu_frame", gpu.ms});
  gpu.renderer = result.renderer;
  gpu.stages = result.stages;
  gpu.max_coefficient_difference = MaxCoefficientDifference(result.coefficients, report.coefficients);
  report.coefficients = result.coefficients;
  report.constants = result.constants;
  for (std::size_t r = 0; r < report.program_constants.size(); ++r) {
    report.program_constants[r].value = result.constants.registers[r];
  }
  irradiance = std::move(result.irradiance);
  return {};
}

}  // namespace vs11::irradiance
