#include "vm/gl/gl_compute.h"

#include <GLES3/gl31.h>

#include <cstdio>

#include <fmt/format.h>

#include "vm/gl/gl_context.h"
#include "vm/gl/gl_engine.h"
#include "vm/gl/gl_runner.h"

namespace vs11::gl {

bool OffersCompute(const GlContext& context) {
  int major = 0, minor = 0;
  return std::sscanf(context.version().c_str(), "OpenGL ES %d.%d", &major, &minor) == 2 &&
         (major > 3 || (major == 3 && minor >= 1));
}

translate::TranslateOptions GlComputeTranslateOptions(const EngineOptions& options, int constant_count, bool es32) {
  translate::TranslateOptions translation = GlTranslateOptions(options, constant_count, es32);
  translation.target = es32 ? translate::Target::kGlslEs320 : translate::Target::kGlslEs310;
  translation.stage = translate::Stage::kCompute;
  return translation;
}

Result<unsigned> LinkComputeProgram(const std::string& source) {
  const Result<unsigned> shader = CompileShader(GL_COMPUTE_SHADER, source);
  if (!shader) return shader.error();
  const GLuint program = glCreateProgram();
  glAttachShader(program, *shader);
  glDeleteShader(*shader);
  return LinkAttachedProgram(program, "compute program");
}

Result<std::unique_ptr<ComputeRun>> ComputeRun::Create(const std::string& compute_source) {
  std::unique_ptr<ComputeRun> run(new ComputeRun());
  const Result<unsigned> program = LinkComputeProgram(compute_source);
  if (!program) return program.error();
  run->program_ = *program;
  GLint max_groups = 0;
  glGetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_COUNT, 0, &max_groups);
  if (max_groups > 0) run->max_groups_x_ = static_cast<std::uint32_t>(max_groups);
  glGenBuffers(1, &run->layout_buffer_);
  glBindBuffer(GL_UNIFORM_BUFFER, run->layout_buffer_);
  glBufferData(GL_UNIFORM_BUFFER, sizeof(translate::ComputeLayoutBlock), nullptr, GL_DYNAMIC_DRAW);
  glGenBuffers(1, &run->constants_buffer_);
  if (Status created = GlOk("creating the compute program's buffers"); !created) return created.error();
  return run;
}

Result<std::unique_ptr<ComputeRun>> ComputeRun::Create(const Program& program,
                                                       const translate::TranslateOptions& options) {
  return Create(translate::TranslateToGlsl(program, options));
}

ComputeRun::~ComputeRun() {
  glDeleteBuffers(1, &constants_buffer_);
  glDeleteBuffers(1, &layout_buffer_);
  glDeleteProgram(program_);
}

void ComputeRun::BindConstantBuffer(unsigned buffer, std::size_t offset, int rows) {
  bound_constants_ = buffer;
  bound_offset_ = offset;
  bound_rows_ = static_cast<std::size_t>(rows);
}

Status ComputeRun::SetConstants(const std::vector<float>& rows) {
  glBindBuffer(GL_UNIFORM_BUFFER, constants_buffer_);
  glBufferData(GL_UNIFORM_BUFFER, static_cast<GLsizeiptr>(rows.size() * sizeof(float)), rows.data(), GL_DYNAMIC_DRAW);
  BindConstantBuffer(constants_buffer_, 0, static_cast<int>(rows.size() / 4));
  return GlOk("uploading the constants");
}

Status ComputeRun::Dispatch(translate::ComputeLayoutBlock layout, unsigned input_buffer, unsigned output_buffer,
                            std::size_t vertex_count) {
  if (vertex_count == 0) return {};
  if (vertex_count > 0xFFFFFFFFu) {
    return Failure(DiagnosticCode::kGlError,
                   fmt::format("{} vertices in one dispatch: the compute translation counts vertices in 32 bits",
                               vertex_count));
  }
  layout.vertex_count = static_cast<std::uint32_t>(vertex_count);
  layout.opaque_zero = 0;
  glUseProgram(program_);
  glBindBuffer(GL_UNIFORM_BUFFER, layout_buffer_);
  glBufferSubData(GL_UNIFORM_BUFFER, 0, sizeof layout, &layout);
  glBindBufferBase(GL_UNIFORM_BUFFER, translate::kComputeLayoutBinding, layout_buffer_);
  if (bound_constants_ != 0) {
    glBindBufferRange(GL_UNIFORM_BUFFER, translate::kComputeConstantsBinding, bound_constants_,
                      static_cast<GLintptr>(bound_offset_), static_cast<GLsizeiptr>(bound_rows_ * 16));
  }
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, translate::kComputeInputsBinding, input_buffer);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, translate::kComputeOutputsBinding, output_buffer);
  const std::array<std::uint32_t, 2> groups = translate::ComputeDispatchSize(vertex_count, max_groups_x_);
  glDispatchCompute(groups[0], groups[1], 1);
  // Mapping and buffer reads (the engine's read-back, a following pass's vertex fetch or copy) see
  // the stores; another shader's storage reads of them as well.
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT | GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT);
  return GlOk("dispatching the compute translation");
}

}  // namespace vs11::gl
