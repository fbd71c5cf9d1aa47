#include "vm/gl/gl_runner.h"

#include <GLES3/gl3.h>

#include <cstdlib>
#include <cstring>

#include <fmt/format.h>

#include "vm/gl/gl_context.h"

namespace vs11::gl {
namespace {

// OpenGL ES needs a fragment shader to link a program, even when rasterisation is discarded. It takes
// the vertex shader's first line, its #version, since the shaders of a program share one version.
std::string FragmentSourceFor(const std::string& vertex_source) {
  return vertex_source.substr(0, vertex_source.find('\n') + 1) +
         "precision highp float;\nout vec4 colour;\nvoid main() { colour = vec4(0.0); }\n";
}

}  // namespace

Result<GLuint> CompileShader(GLenum kind, const std::string& source) {
  const GLuint shader = glCreateShader(kind);
  const char* text = source.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok == GL_TRUE) return shader;
  char log[2048] = {};
  glGetShaderInfoLog(shader, sizeof log, nullptr, log);
  glDeleteShader(shader);
  return Failure(DiagnosticCode::kGlCompile, fmt::format("shader does not compile: {}", log));
}

Result<unsigned> LinkAttachedProgram(unsigned program, const char* what) {
  glLinkProgram(program);
  GLint ok = GL_FALSE;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (ok == GL_TRUE) return program;
  char log[2048] = {};
  glGetProgramInfoLog(program, sizeof log, nullptr, log);
  glDeleteProgram(program);
  return Failure(DiagnosticCode::kGlCompile, fmt::format("{} does not link: {}", what, log));
}

Status GlOk(const char* what) {
  const GLenum code = glGetError();
  if (code == GL_NO_ERROR) return {};
  return Failure(DiagnosticCode::kGlError, fmt::format("{}: GL error 0x{:04X}", what, code));
}

Result<std::vector<float>> ReadBufferFloats(unsigned buffer, std::size_t count) {
  glBindBuffer(GL_COPY_READ_BUFFER, buffer);
  const void* mapped =
      glMapBufferRange(GL_COPY_READ_BUFFER, 0, static_cast<GLsizeiptr>(count * sizeof(float)), GL_MAP_READ_BIT);
  if (mapped == nullptr) {
    if (Status mapping = GlOk("glMapBufferRange"); !mapping) return mapping.error();
    return Failure(DiagnosticCode::kGlError, "glMapBufferRange returned no pointer");
  }
  std::vector<float> values(count);
  std::memcpy(values.data(), mapped, count * sizeof(float));
  glUnmapBuffer(GL_COPY_READ_BUFFER);
  if (Status read = GlOk("reading a buffer"); !read) return read.error();
  return values;
}

Result<std::string> CreateLlvmpipeContext(std::optional<int> lp_threads) {
  if (lp_threads) {
    setenv("LP_NUM_THREADS", std::to_string(*lp_threads).c_str(), 1);
  } else {
    unsetenv("LP_NUM_THREADS");
  }
  // Current on this thread until the process ends, as the callers (a test's fixture, the bench's
  // child process) expect.
  static std::unique_ptr<GlContext> context;
  Result<std::unique_ptr<GlContext>> created = GlContext::Create(std::nullopt);
  if (!created) return created.error();
  context = std::move(created).value();
  if (Status current = context->MakeCurrent(); !current) return current.error();
  return context->renderer();
}

Result<unsigned> LinkTransformFeedbackProgram(const std::string& vertex_source,
                                              const std::vector<std::string>& varyings) {
  const Result<GLuint> vertex_shader = CompileShader(GL_VERTEX_SHADER, vertex_source);
  if (!vertex_shader) return vertex_shader.error();
  const GLuint vertex = *vertex_shader;
  const Result<GLuint> fragment_shader = CompileShader(GL_FRAGMENT_SHADER, FragmentSourceFor(vertex_source));
  if (!fragment_shader) {
    glDeleteShader(vertex);
    return fragment_shader.error();
  }
  const GLuint fragment = *fragment_shader;
  const GLuint program = glCreateProgram();
  glAttachShader(program, vertex);
  glAttachShader(program, fragment);
  std::vector<const char*> names;
  for (const std::string& v : varyings) names.push_back(v.c_str());
  glTransformFeedbackVaryings(program, static_cast<GLsizei>(names.size()), names.data(), GL_INTERLEAVED_ATTRIBS);
  glDeleteShader(vertex);
  glDeleteShader(fragment);
  return LinkAttachedProgram(program, "program");
}

Result<std::unique_ptr<TransformFeedbackRun>> TransformFeedbackRun::Create(
    const std::string& vertex_source, const std::vector<std::string>& varyings, int output_floats,
    const std::vector<GlAttribute>& attributes, const std::vector<float>& constants, std::size_t vertex_count) {
  std::unique_ptr<TransformFeedbackRun> run(new TransformFeedbackRun());
  const Result<unsigned> program = LinkTransformFeedbackProgram(vertex_source, varyings);
  if (!program) return program.error();
  run->program_ = *program;
  glUseProgram(run->program_);
  if (!constants.empty()) {
    const GLint location = glGetUniformLocation(run->program_, "c");
    if (location < 0) return Failure(DiagnosticCode::kGlCompile, "the shader has no uniform vec4 c[]");
    glUniform4fv(location, static_cast<GLsizei>(constants.size() / 4), constants.data());
  }

  glGenVertexArrays(1, &run->vertex_array_);
  glBindVertexArray(run->vertex_array_);
  for (const GlAttribute& attribute : attributes) {
    GLuint buffer = 0;
    glGenBuffers(1, &buffer);
    run->input_buffers_.push_back(buffer);
    glBindBuffer(GL_ARRAY_BUFFER, buffer);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(attribute.data.size() * sizeof(float)),
                 attribute.data.data(), GL_STATIC_DRAW);
    glVertexAttribPointer(static_cast<GLuint>(attribute.location), attribute.components, GL_FLOAT, GL_FALSE, 0,
                          nullptr);
    glEnableVertexAttribArray(static_cast<GLuint>(attribute.location));
    run->vertex_count_ = attribute.data.size() / static_cast<std::size_t>(attribute.components);
  }
  if (vertex_count != 0) run->vertex_count_ = vertex_count;
  run->output_floats_ = output_floats;
  glGenBuffers(1, &run->output_buffer_);
  glBindBuffer(GL_TRANSFORM_FEEDBACK_BUFFER, run->output_buffer_);
  glBufferData(GL_TRANSFORM_FEEDBACK_BUFFER,
               static_cast<GLsizeiptr>(run->vertex_count_ * static_cast<std::size_t>(output_floats) * sizeof(float)),
               nullptr, GL_STREAM_READ);
  glGenQueries(1, &run->query_);
  if (Status created = GlOk("creating the buffers"); !created) return created.error();
  return run;
}

TransformFeedbackRun::~TransformFeedbackRun() {
  glDeleteQueries(1, &query_);
  glDeleteBuffers(1, &output_buffer_);
  glDeleteBuffers(static_cast<GLsizei>(input_buffers_.size()), input_buffers_.data());
  glDeleteVertexArrays(1, &vertex_array_);
  glDeleteProgram(program_);
}

Status TransformFeedbackRun::Draw(int draws) {
  glUseProgram(program_);
  glBindVertexArray(vertex_array_);
  glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, output_buffer_);
  for (int i = 0; i < draws; ++i) {
    glBeginTransformFeedback(GL_POINTS);
    glDrawArrays(GL_POINTS, 0, static_cast<GLsizei>(vertex_count_));
    glEndTransformFeedback();
  }
  glFinish();
  return GlOk("drawing with transform feedback");
}

Result<std::vector<float>> TransformFeedbackRun::DrawAndRead() {
  glBeginQuery(GL_TRANSFORM_FEEDBACK_PRIMITIVES_WRITTEN, query_);
  if (Status drawn = Draw(1); !drawn) return drawn.error();
  glEndQuery(GL_TRANSFORM_FEEDBACK_PRIMITIVES_WRITTEN);
  GLuint written = 0;
  glGetQueryObjectuiv(query_, GL_QUERY_RESULT, &written);
  if (written != vertex_count_) {
    return Failure(DiagnosticCode::kGlError,
                   fmt::format("transform feedback wrote {} of {} vertices", written, vertex_count_));
  }
  return ReadBufferFloats(output_buffer_, vertex_count_ * static_cast<std::size_t>(output_floats_));
}

}  // namespace vs11::gl
