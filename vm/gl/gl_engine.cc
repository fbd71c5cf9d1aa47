#include "vm/gl/gl_engine.h"

#include <GLES3/gl3.h>

#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "vm/engines/engine_factory.h"
#include "vm/engines/static_flow_engine.h"
#include "vm/gl/gl_compute.h"
#include "vm/gl/gl_compute_engine.h"
#include "vm/gl/gl_context.h"
#include "vm/gl/gl_runner.h"

namespace vs11::gl {
namespace {

// Vertices per draw: bounds the staging and capture buffers (46 floats a vertex at most, so 12 MB)
// whatever the call's size.
constexpr std::size_t kVerticesPerDraw = std::size_t{1} << 16;

// An output register the program writes, captured as `components` floats at `offset` of a vertex.
struct Capture {
  int slot = 0;
  int components = 4;
  int offset = 0;
};

class GlEngine final : public Engine, public GlPathOwner {
 public:
  GlEngine(const Program& program, const EngineOptions& options, std::unique_ptr<GlContext> context)
      : program_(program), options_(options), context_(std::move(context)) {}
  ~GlEngine() override;

  // Translates for a bank of `constant_count` registers, links, and makes the buffers.
  Status Build(int constant_count);
  Status Run(const VertexArrays& inputs, VertexArrays& outputs) override;
  Status SetConstants(const ConstantBank& api_constants) override;
  GlPath path() const override { return GlPath::kTransformFeedback; }

 private:
  void DeleteObjects();
  Status RunDraw(const VertexArrays& inputs, std::size_t first, std::size_t count, VertexArrays& outputs);
  // Keeps a failed `status` as failure_; whether it succeeded.
  bool Keep(const Status& status);
  void UploadInputs(const VertexArrays& inputs, std::size_t first, std::size_t count);
  void ScatterOutputs(const float* captured, std::size_t first, std::size_t count, VertexArrays& outputs) const;

  Program program_;
  EngineOptions options_;
  std::unique_ptr<GlContext> context_;
  // Why a SetConstants or Run failed: every later call returns it (vm/core/machine.h's Engine).
  Status failure_;
  int constant_count_ = 0;
  GLuint program_object_ = 0, vertex_array_ = 0, output_buffer_ = 0, query_ = 0;
  GLint constants_location_ = -1;
  std::vector<int> active_inputs_;  // the vN the linked shader reads
  std::vector<GLuint> input_buffers_ = std::vector<GLuint>(kInputRegisterCount, 0);
  std::vector<Capture> captures_;
  int output_floats_ = 0;  // per vertex
  std::vector<float> staging_;
};

GlEngine::~GlEngine() {
  ScopedCurrent current(*context_);
  if (current.ok()) DeleteObjects();
}

void GlEngine::DeleteObjects() {
  glDeleteQueries(1, &query_);
  glDeleteBuffers(1, &output_buffer_);
  glDeleteBuffers(static_cast<GLsizei>(input_buffers_.size()), input_buffers_.data());
  glDeleteVertexArrays(1, &vertex_array_);
  glDeleteProgram(program_object_);
  query_ = output_buffer_ = vertex_array_ = program_object_ = 0;
  std::fill(input_buffers_.begin(), input_buffers_.end(), 0);
}

// The vN among the linked program's active attributes.
std::vector<int> ActiveInputs(GLuint program) {
  GLint count = 0;
  glGetProgramiv(program, GL_ACTIVE_ATTRIBUTES, &count);
  std::vector<int> registers;
  for (GLint i = 0; i < count; ++i) {
    char name[64] = {};
    GLint size = 0;
    GLenum type = 0;
    glGetActiveAttrib(program, static_cast<GLuint>(i), sizeof name, nullptr, &size, &type, name);
    const GLint location = glGetAttribLocation(program, name);
    if (name[0] == 'v' && location >= 0 && location < kInputRegisterCount) registers.push_back(location);
  }
  std::sort(registers.begin(), registers.end());
  return registers;
}

bool GlEngine::Keep(const Status& status) {
  if (!status) failure_ = status;
  return status.ok();
}

Status GlEngine::Build(int constant_count) {
  ScopedCurrent current(*context_);
  if (!current.ok()) return current.status();
  DeleteObjects();
  constant_count_ = constant_count;
  captures_.clear();
  output_floats_ = 0;
  std::vector<std::string> varyings;
  const std::array<WriteMask, kOutputSlotCount> written = WrittenOutputLanes(program_);
  for (int slot = 0; slot < kOutputSlotCount; ++slot) {
    if (written[static_cast<std::size_t>(slot)].bits() == 0) continue;
    const translate::OutputVariable variable = translate::OutputVariableOf(slot, /*exact_on_driver=*/true);
    captures_.push_back({slot, variable.components, output_floats_});
    varyings.push_back(variable.name);
    output_floats_ += variable.components;
  }
  const std::string glsl =
      translate::TranslateToGlsl(program_, GlTranslateOptions(options_, constant_count, context_->es32()));
  const Result<unsigned> linked = LinkTransformFeedbackProgram(glsl, varyings);
  if (!linked) {
    GLint uniform_vectors = 0;
    glGetIntegerv(GL_MAX_VERTEX_UNIFORM_VECTORS, &uniform_vectors);
    Diagnostic error = linked.error();
    error.message += fmt::format(" (the constant bank is c[{}], --max-constants; '{}' allows {} vec4 uniforms)",
                                 constant_count, context_->renderer(), uniform_vectors);
    return error;
  }
  program_object_ = *linked;
  constants_location_ = glGetUniformLocation(program_object_, "c");
  active_inputs_ = ActiveInputs(program_object_);
  glGenVertexArrays(1, &vertex_array_);
  glGenBuffers(static_cast<GLsizei>(input_buffers_.size()), input_buffers_.data());
  glGenBuffers(1, &output_buffer_);
  glGenQueries(1, &query_);
  return GlOk("creating the vertex array and buffers");
}

Status GlEngine::SetConstants(const ConstantBank& api_constants) {
  if (!failure_) return failure_;
  if (api_constants.size() != constant_count_ && !Keep(Build(api_constants.size()))) return failure_;
  if (constants_location_ < 0) return {};  // the program reads no constant from the bank
  ScopedCurrent current(*context_);
  if (!Keep(current.status())) return failure_;
  std::vector<float> floats;
  floats.reserve(static_cast<std::size_t>(api_constants.size()) * 4);
  for (const Vec4f& row : api_constants.values()) floats.insert(floats.end(), row.begin(), row.end());
  glUseProgram(program_object_);
  glUniform4fv(constants_location_, api_constants.size(), floats.data());
  Keep(GlOk("setting the constants"));
  return failure_;
}

Status GlEngine::Run(const VertexArrays& inputs, VertexArrays& outputs) {
  if (failure_ && !captures_.empty() && inputs.count() > 0) {
    ScopedCurrent current(*context_);
    for (std::size_t first = 0; Keep(current.status()) && first < inputs.count(); first += kVerticesPerDraw) {
      if (!Keep(RunDraw(inputs, first, std::min(kVerticesPerDraw, inputs.count() - first), outputs))) break;
    }
  }
  if (!failure_) FillWithNaN(outputs);
  return failure_;
}

// Vertices [first, first + count) of every attribute the shader reads, as vec4s; a register the
// caller does not supply reads (0, 0, 0, 1) as on every engine (GL's current attribute value).
void GlEngine::UploadInputs(const VertexArrays& inputs, std::size_t first, std::size_t count) {
  for (int reg : active_inputs_) {
    const auto location = static_cast<GLuint>(reg);
    if (!inputs.has(reg)) {
      glDisableVertexAttribArray(location);
      glVertexAttrib4f(location, kDefaultInput[0], kDefaultInput[1], kDefaultInput[2], kDefaultInput[3]);
      continue;
    }
    staging_.resize(count * 4);
    for (int c = 0; c < 4; ++c) {
      const float* lane = inputs.lane(reg, c) + first;
      for (std::size_t v = 0; v < count; ++v) staging_[v * 4 + static_cast<std::size_t>(c)] = lane[v];
    }
    glBindBuffer(GL_ARRAY_BUFFER, input_buffers_[static_cast<std::size_t>(reg)]);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(staging_.size() * sizeof(float)), staging_.data(),
                 GL_STREAM_DRAW);
    glVertexAttribPointer(location, 4, GL_FLOAT, GL_FALSE, 0, nullptr);
    glEnableVertexAttribArray(location);
  }
}

void GlEngine::ScatterOutputs(const float* captured, std::size_t first, std::size_t count,
                              VertexArrays& outputs) const {
  const auto stride = static_cast<std::size_t>(output_floats_);
  for (const Capture& capture : captures_) {
    if (!outputs.has(capture.slot)) continue;
    for (int c = 0; c < capture.components; ++c) {  // four: oFog and oPts too (OutputVariableOf)
      float* lane = outputs.lane(capture.slot, c) + first;
      const float* source = captured + capture.offset + c;
      for (std::size_t v = 0; v < count; ++v) lane[v] = source[v * stride];
    }
  }
}

Status GlEngine::RunDraw(const VertexArrays& inputs, std::size_t first, std::size_t count, VertexArrays& outputs) {
  glUseProgram(program_object_);
  glBindVertexArray(vertex_array_);
  UploadInputs(inputs, first, count);
  const std::size_t floats = count * static_cast<std::size_t>(output_floats_);
  glBindBuffer(GL_TRANSFORM_FEEDBACK_BUFFER, output_buffer_);
  glBufferData(GL_TRANSFORM_FEEDBACK_BUFFER, static_cast<GLsizeiptr>(floats * sizeof(float)), nullptr, GL_STREAM_READ);
  glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, output_buffer_);
  glBeginQuery(GL_TRANSFORM_FEEDBACK_PRIMITIVES_WRITTEN, query_);
  glBeginTransformFeedback(GL_POINTS);
  glDrawArrays(GL_POINTS, 0, static_cast<GLsizei>(count));
  glEndTransformFeedback();
  glEndQuery(GL_TRANSFORM_FEEDBACK_PRIMITIVES_WRITTEN);
  if (Status drawn = GlOk("drawing with transform feedback"); !drawn) return drawn;
  GLuint written = 0;
  glGetQueryObjectuiv(query_, GL_QUERY_RESULT, &written);
  if (written != count) {
    return Failure(DiagnosticCode::kGlError,
                   fmt::format("transform feedback captured {} of {} vertices", written, count));
  }
  const void* mapped = glMapBufferRange(GL_TRANSFORM_FEEDBACK_BUFFER, 0,
                                        static_cast<GLsizeiptr>(floats * sizeof(float)), GL_MAP_READ_BIT);
  if (mapped == nullptr) {
    if (Status mapping = GlOk("glMapBufferRange"); !mapping) return mapping;
    return Failure(DiagnosticCode::kGlError, "glMapBufferRange returned no pointer");
  }
  ScatterOutputs(static_cast<const float*>(mapped), first, count, outputs);
  glUnmapBuffer(GL_TRANSFORM_FEEDBACK_BUFFER);
  return GlOk("reading the transform-feedback buffer");
}

}  // namespace

translate::TranslateOptions GlTranslateOptions(const EngineOptions& options, int constant_count, bool es32) {
  translate::TranslateOptions translation;
  translation.target = es32 ? translate::Target::kGlslEs320 : translate::Target::kGlslEs300;
  translation.clip = translate::ClipSpace::kD3d;
  translation.constant_count = constant_count;
  translation.exact_on_driver = true;
  translation.float_rules = options.float_rules;
  return translation;
}

std::optional<GlPath> GlPathOf(const Engine& engine) {
  const auto* owner = dynamic_cast<const GlPathOwner*>(&engine);
  if (owner == nullptr) return std::nullopt;
  return owner->path();
}

namespace {

// `error` with `prefix` before its message: what failed, then why.
Diagnostic Prefixed(Diagnostic error, std::string_view prefix) {
  error.message.insert(0, prefix);
  return error;
}

}  // namespace

Result<std::unique_ptr<Engine>> MakeGlEngine(const Program& program, const ConstantBank& api_constants,
                                             const EngineOptions& options) {
  // A later model's program runs as its straight-line specialisations, each translated and linked once
  // (vm/engines/static_flow_engine.h), as a driver compiles a shader per set of i#/b# values.
  if (!Info(program.model()).runs) return MakeStaticFlowEngine(program, api_constants, options, "gl", &MakeGlEngine);
  const GlOptions gl_options = options.settings.Get<GlOptions>();
  Result<std::unique_ptr<GlContext>> context = GlContext::Create(gl_options.device);
  if (!context) return Prefixed(context.error(), "the gl engine has no OpenGL ES 3.0 device: ");
  const std::string renderer = (*context)->renderer();
  const std::string on_renderer = fmt::format("the gl engine on '{}': ", renderer);
  const bool compute = OffersCompute(**context);
  if (gl_options.path == GlPath::kCompute && !compute) {
    return Failure(DiagnosticCode::kGlUnavailable,
                   fmt::format("{}--gl-path compute needs OpenGL ES 3.1, the context is '{}'", on_renderer,
                               (*context)->version()));
  }
  if (compute && gl_options.path != GlPath::kTransformFeedback) {
    Result<std::unique_ptr<Engine>> engine =
        MakeGlComputeEngine(program, api_constants, options, std::move(context).value());
    if (!engine) return Prefixed(engine.error(), fmt::format("the gl engine on '{}' (compute path): ", renderer));
    return engine;
  }
  auto engine = std::make_unique<GlEngine>(program, options, std::move(context).value());
  if (Status built = engine->Build(api_constants.size()); !built) return Prefixed(built.error(), on_renderer);
  if (Status set = engine->SetConstants(api_constants); !set) return Prefixed(set.error(), on_renderer);
  return engine;
}

void RegisterGlEngine() {
  RegisterEngine({"gl", "",
                  "the GLSL ES translation on an OpenGL ES driver through EGL (a compute shader on ES 3.1, else transform "
                  "feedback): Mesa's llvmpipe, or --gl-device N",
                  &MakeGlEngine});
}

}  // namespace vs11::gl
