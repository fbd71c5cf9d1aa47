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

Result<std::unique_ptr<ProgramStage>> ProgramStage::Create(GpuFrame& frame, const PaperProgram& program,
                                                           std::span<const glm::vec3> normals) {
  std::unique_ptr<ProgramStage> stage(new ProgramStage(frame));
  ScopedCurrent current(frame.context());
  if (!current.ok()) return current.status().error();
  Result<std::unique_ptr<vs11::gl::ComputeRun>> run = vs11::gl::ComputeRun::Create(
      program.program(),
      vs11::gl::GlComputeTranslateOptions(EngineOptions{}, frame.constant_count(), frame.context().es32()));
  if (!run) return run.error();
  stage->run_ = std::move(run).value();
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
  if (Status created = GlOk("creating the program stage's buffers"); !created) return created.error();
  return stage;
}

ProgramStage::~ProgramStage() {
  ScopedCurrent current(frame_.context());
  if (!current.ok()) return;
  run_.reset();
  glDeleteBuffers(1, &input_);
  glDeleteBuffers(1, &output_);
}

Status ProgramStage::Run() {
  ScopedCurrent current(frame_.context());
  if (!current.ok()) return current.status();
  return run_->Dispatch(layout_, input_, output_, vertex_count_);
}

Result<std::vector<glm::vec3>> ProgramStage::Read() {
  ScopedCurrent current(frame_.context());
  if (!current.ok()) return current.status().error();
  const Result<std::vector<float>> stored = vs11::gl::ReadBufferFloats(output_, vertex_count_ * kOutputStride);
  if (!stored) return stored.error();
  std::vector<glm::vec3> values(vertex_count_);
  for (std::size_t v = 0; v < vertex_count_; ++v) {
    const float* out = stored->data() + v * kOutputStride;
    values[v] = glm::vec3(out[0], out[1], out[2]);
  }
  return values;
}

}  // namespace vs11::irradiance::gpu
