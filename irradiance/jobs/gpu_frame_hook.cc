#include "irradiance/jobs/gpu_frame_hook.h"

#include <algorithm>
#include <cmath>

namespace vs11::irradiance {

std::optional<std::string> WhyNotOnGpu(bool cube, ShOrder order, ShWindow window) {
  if (!cube) return "a lat-long environment is projected in place on the CPU";
  if (order != ShOrder::kOrder2) return "the GPU frame runs the paper's program (--order order2) only";
  if (window != ShWindow::kNone) return "the GPU frame applies no --window";
  return std::nullopt;
}

double MaxCoefficientDifference(const Sh9Rgb& gpu, const Sh9Rgb& cpu) {
  double largest = 0.0, difference = 0.0;
  for (int lm = 0; lm < kSh9Coefficients; ++lm) {
    for (int c = 0; c < 3; ++c) {
      largest = std::max(largest, std::abs(cpu.coefficients[lm][c]));
      difference = std::max(difference, std::abs(gpu.coefficients[lm][c] - cpu.coefficients[lm][c]));
    }
  }
  return largest > 0.0 ? difference / largest : difference;
}

nlohmann::ordered_json GpuFrameJson(const GpuFrameReport& gpu) {
  nlohmann::ordered_json json = {{"renderer", gpu.renderer}, {"stages", gpu.stages}};
  if (!gpu.cpu_reason.empty()) json["cpu_reason"] = gpu.cpu_reason;
  json["max_coefficient_difference"] = gpu.max_coefficient_difference;
  json["ms"] = gpu.ms;
  return json;
}

}  // namespace vs11::irradiance
