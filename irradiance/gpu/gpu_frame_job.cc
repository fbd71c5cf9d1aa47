#include "irradiance/gpu/gpu_frame_job.h"

#include <memory>
#include <vector>

#include "irradiance/gpu/gpu_frame.h"
#include "irradiance/gpu/program_stage.h"

namespace vs11::irradiance::gpu {

GpuFrameHook MakeGpuFrameHook(std::optional<int> device) {
  return [device](const GpuFrameRequest& request, GpuFrameResult& result) -> Status {
    const int bank_size = request.program.Constants(SevenConstants{}).size();
    Result<std::unique_ptr<GpuFrame>> frame =
        GpuFrame::Create(device, request.basis, request.level, bank_size, request.program.constant_base());
    if (!frame) return frame.error();
    std::unique_ptr<ProgramStage> program;
    if (!request.normals.empty()) {
      const std::vector<glm::vec3> normals(request.normals.begin(), request.normals.end());
      Result<std::unique_ptr<ProgramStage>> stage = ProgramStage::Create(**frame, request.program, normals);
      if (!stage) return stage.error();
      program = std::move(stage).value();
    }
    if (Status uploaded = (*frame)->Upload(request.environment); !uploaded) return uploaded;
    if (Status projected = (*frame)->Project(); !projected) return projected;
    if (program) {
      if (Status ran = program->Run(); !ran) return ran;
    }
    result.renderer = (*frame)->context().renderer();
    result.stages = {"upload"};
    if (request.level > 0) result.stages.push_back("env_mips");
    result.stages.insert(result.stages.end(), {"projection", "constants"});
    if (program) result.stages.push_back("program");
    const Result<Sh9Rgb> coefficients = (*frame)->ReadCoefficients();
    if (!coefficients) return coefficients.error();
    const Result<SevenConstants> constants = (*frame)->ReadConstants();
    if (!constants) return constants.error();
    result.coefficients = *coefficients;
    result.constants = *constants;
    result.error_factor = GpuProjectionErrorFactor(request.basis.face_size, request.level);
    if (program) {
      const Result<std::vector<glm::vec3>> values = program->Read();
      if (!values) return values.error();
      result.irradiance.assign(values->begin(), values->end());
    }
    return {};
  };
}

}  // namespace vs11::irradiance::gpu
