#include "irradiance/gpu/program_stage.h"

#include <GLES3/gl31.h>

#include "vm/gl/gl_runner.h"

namespace vs11::irradiance::gpu {

using vs11::gl::GlOk;
using vs11::gl::ScopedCurrent;

namespace {

// Every vertex's output register as four floats, vertex after vertex.
constexpr std::uint32_t kOutputStride = 4;

}  // namespace

std::unique_ptr<ProgramStage> ProgramStage::Create(GpuFrame& frame, const PaperProgram& program,
                                                   std::span<const glm::vec3> normals, std::string& error) {
  std::unique_ptr<ProgramStage> stage(new ProgramStage(frame));
  ScopedCurrent current(frame.context(), error);
  if (!current.ok()) return nullptr;
  stage->run_ = vs11::gl::ComputeRun::Create(
      program.program(),
      vs11::gl::GlComputeTranslateOptions(EngineOptions{}, frame.constant_count(), frame.context().es32()), error);
  if (!stage->run_) return nullptr;
  stage->run_->BindConstantBuffer(frame.constant_buffer(), 0, frame.constant_count());

  stage->vertex_count_ = normals.size();
  std::vector<float> inputs;
  inputs.reserve(normals.size() * 4);
  for (const glm::vec3& n : normals) inputs.insert(inputs.end(), {n.x, n.y, n.z, 1.0f});
  stage->layout_.SetInterleavedInput(program.normal_register(), 0, 4);
  stage->layout_.SetOutput(program.output_slot(), {0, 1, 2, 3}, kOutputStride);
  glGenBuffers(1, &stage->input_);
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, stage->input_);
  glBufferData(GL_SHADER_STORAGE_BUFFER, static_cast<GLsizeiptr>(inputs.size() * sizeof(float)), inputs.data(),
               GL_STATIC_DRAW);
  glGenBuffers(1, &stage->output_);
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, stage->output_);
  glBufferData(GL_SHADER_STORAGE_BUFFER, static_cast<GLsizeiptr>(normals.size() * kOutputStride * sizeof(float)),
               nullptr, GL_DYNAMIC_READ);
  if (!GlOk("creating the program stage's buffers", error)) return nullptr;
  return stage;
}

ProgramStage::~ProgramStage() {
  std::string ignored;
  ScopedCurrent current(frame_.context(), ignored);
  if (!current.ok()) return;
  run_.reset();
  glDeleteBuffers(1, &input_);
  glDeleteBuffers(1, &output_);
}

bool ProgramStage::Run(std::string& error) {
  ScopedCurrent current(frame_.context(), error);
  if (!current.ok()) return false;
  return run_->Dispatch(layout_, input_, output_, vertex_count_, error);
}

std::optional<std::vector<glm::vec3>> ProgramStage::Read(std::string& error) {
  ScopedCurrent current(frame_.context(), error);
  if (!current.ok()) return std::nullopt;
  const std::optional<std::vector<float>> stored =
      vs11::gl::ReadBufferFloats(output_, vertex_count_ * kOutputStride, error);
  if (!stored) return std::nullopt;
  std::vector<glm::vec3> values(vertex_count_);
  for (std::size_t v = 0; v < vertex_count_; ++v) {
    const float* out = stored->data() + v * kOutputStride;
    values[v] = glm::vec3(out[0], out[1], out[2]);
  }
  return values;
}

}  // namespace vs11::irradiance::gpu
