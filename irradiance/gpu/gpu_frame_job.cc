#include "irradiance/gpu/gpu_frame_job.h"

#include <memory>
#include <string>
#include <vector>

#include "irradiance/gpu/gpu_frame.h"
#include "irradiance/gpu/program_stage.h"

namespace vs11::irradiance::gpu {

GpuFrameHook MakeGpuFrameHook(std::optional<int> device) {
  return [device](const GpuFrameRequest& request, GpuFrameResult& result) -> std::optional<std::string> {
    std::string error;
    const int bank_size = request.program.Constants(SevenConstants{}).size();
    std::unique_ptr<GpuFrame> frame = GpuFrame::Create(device, request.basis, request.level, bank_size,
                                                       request.program.constant_base(), error);
    if (!frame) return error;
    std::unique_ptr<ProgramStage> program;
    if (!request.normals.empty()) {
      const std::vector<glm::vec3> normals(request.normals.begin(), request.normals.end());
      program = ProgramStage::Create(*frame, request.program, normals, error);
      if (!program) return error;
    }
    if (!frame->Upload(request.environment, error) || !frame->Project(error)) return error;
    if (program && !program->Run(error)) return error;
    result.renderer = frame->context().renderer();
    result.stages = {"upload"};
    if (request.level > 0) result.stages.push_back("env_mips");
    result.stages.insert(result.stages.end(), {"projection", "constants"});
    if (program) result.stages.push_back("program");
    const std::optional<Sh9Rgb> coefficients = frame->ReadCoefficients(error);
    const std::optional<SevenConstants> constants = frame->ReadConstants(error);
    if (!coefficients || !constants) return error;
    result.coefficients = *coefficients;
    result.constants = *constants;
    result.error_factor = GpuProjectionErrorFactor(request.basis.face_size, request.level);
    if (program) {
      const std::optional<std::vector<glm::vec3>> values = program->Read(error);
      if (!values) return error;
      result.irradiance.assign(values->begin(), values->end());
    }
    return std::nullopt;
  };
}

}  // namespace vs11::irradiance::gpu
