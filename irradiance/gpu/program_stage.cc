#include "irradiance/gpu/program_stage.h"

#include <GLES3/gl31.h>

#include <cstring>
#include <regex>

#include <fmt/format.h>

#include "vm/gl/gl_engine.h"
#include "vm/gl/gl_runner.h"
#include "vm/translate/translate.h"

namespace vs11::irradiance::gpu {

using vs11::gl::GlOk;
using vs11::gl::ScopedCurrent;

std::optional<std::string> WithUniformBlockBank(const std::string& translation) {
  static const std::regex bank(R"(uniform vec4 c\[(\d+)\];)");
  std::smatch match;
  if (!std::regex_search(translation, match, bank)) return std::nullopt;
  return match.prefix().str() + fmt::format("layout(std140) uniform Vs11Constants {{ vec4 c[{}]; }};", match[1].str()) +
         match.suffix().str();
}

std::unique_ptr<ProgramStage> ProgramStage::Create(GpuFrame& frame, const PaperProgram& program,
                                                   std::span<const glm::vec3> normals, std::string& error) {
  std::unique_ptr<ProgramStage> stage(new ProgramStage(frame));
  ScopedCurrent current(frame.context(), error);
  if (!current.ok()) return nullptr;
  const std::string translation = translate::TranslateToGlsl(
      program.program(), vs11::gl::GlTranslateOptions(EngineOptions{}, frame.constant_count(), frame.context().es32()));
  const std::optional<std::string> source = WithUniformBlockBank(translation);
  if (!source) {
    error = "the program's translation declares no constant bank";
    return nullptr;
  }
  const translate::OutputVariable output = translate::OutputVariableOf(program.output_slot(), /*exact_on_driver=*/true);
  stage->output_components_ = output.components;
  stage->program_ = vs11::gl::LinkTransformFeedbackProgram(*source, {output.name}, error);
  if (stage->program_ == 0) return nullptr;
  const GLuint block = glGetUniformBlockIndex(stage->program_, "Vs11Constants");
  if (block == GL_INVALID_INDEX) {
    error = "the linked program has no Vs11Constants block";
    return nullptr;
  }
  glUniformBlockBinding(stage->program_, block, 0);
  const GLint location = glGetAttribLocation(stage->program_, fmt::format("v{}", program.normal_register()).c_str());

  stage->vertex_count_ = normals.size();
  std::vector<float> inputs;
  inputs.reserve(normals.size() * 4);
  for (const glm::vec3& n : normals) inputs.insert(inputs.end(), {n.x, n.y, n.z, 1.0f});
  glGenVertexArrays(1, &stage->vertex_array_);
  glBindVertexArray(stage->vertex_array_);
  glGenBuffers(1, &stage->input_);
  glBindBuffer(GL_ARRAY_BUFFER, stage->input_);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(inputs.size() * sizeof(float)), inputs.data(), GL_STATIC_DRAW);
  if (location >= 0) {
    glVertexAttribPointer(static_cast<GLuint>(location), 4, GL_FLOAT, GL_FALSE, 0, nullptr);
    glEnableVertexAttribArray(static_cast<GLuint>(location));
  }
  glGenBuffers(1, &stage->output_);
  glBindBuffer(GL_TRANSFORM_FEEDBACK_BUFFER, stage->output_);
  glBufferData(GL_TRANSFORM_FEEDBACK_BUFFER,
               static_cast<GLsizeiptr>(normals.size() * static_cast<std::size_t>(output.components) * sizeof(float)),
               nullptr, GL_DYNAMIC_READ);
  if (!GlOk("creating the program stage's buffers", error)) return nullptr;
  return stage;
}

ProgramStage::~ProgramStage() {
  std::string ignored;
  ScopedCurrent current(frame_.context(), ignored);
  if (!current.ok()) return;
  glDeleteBuffers(1, &input_);
  glDeleteBuffers(1, &output_);
  glDeleteVertexArrays(1, &vertex_array_);
  glDeleteProgram(program_);
}

bool ProgramStage::Run(std::string& error) {
  ScopedCurrent current(frame_.context(), error);
  if (!current.ok()) return false;
  glUseProgram(program_);
  glBindVertexArray(vertex_array_);
  glBindBufferBase(GL_UNIFORM_BUFFER, 0, frame_.constant_buffer());
  glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, output_);
  glBeginTransformFeedback(GL_POINTS);
  glDrawArrays(GL_POINTS, 0, static_cast<GLsizei>(vertex_count_));
  glEndTransformFeedback();
  return GlOk("running the program with transform feedback", error);
}

std::optional<std::vector<glm::vec3>> ProgramStage::Read(std::string& error) {
  ScopedCurrent current(frame_.context(), error);
  if (!current.ok()) return std::nullopt;
  const std::size_t floats = vertex_count_ * static_cast<std::size_t>(output_components_);
  glBindBuffer(GL_TRANSFORM_FEEDBACK_BUFFER, output_);
  const auto* mapped = static_cast<const float*>(glMapBufferRange(
      GL_TRANSFORM_FEEDBACK_BUFFER, 0, static_cast<GLsizeiptr>(floats * sizeof(float)), GL_MAP_READ_BIT));
  if (mapped == nullptr) {
    if (GlOk("glMapBufferRange", error)) error = "glMapBufferRange returned no pointer";
    return std::nullopt;
  }
  std::vector<glm::vec3> values(vertex_count_);
  for (std::size_t v = 0; v < vertex_count_; ++v) {
    const float* out = mapped + v * static_cast<std::size_t>(output_components_);
    values[v] = glm::vec3(out[0], output_components_ > 1 ? out[1] : 0.0f, output_components_ > 2 ? out[2] : 0.0f);
  }
  glUnmapBuffer(GL_TRANSFORM_FEEDBACK_BUFFER);
  if (!GlOk("reading the program's outputs", error)) return std::nullopt;
  return values;
}

}  // namespace vs11::irradiance::gpu
