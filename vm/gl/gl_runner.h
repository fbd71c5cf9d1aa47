// Vertex shaders run over vertex buffers with transform feedback and GL_RASTERIZER_DISCARD, on an
// OpenGL ES 3.0 context (gl_context.h): the translator's tests and bench/compare_llvmpipe.
#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace vs11::gl {

// Creates a context on Mesa's llvmpipe (GlContext::Create(nullopt)) that stays current on the calling
// thread for the rest of the process. `lp_threads`, when set, goes to LP_NUM_THREADS, which Mesa reads
// when the display is initialised (so only the process's first display honours it). Returns
// GL_RENDERER, or nullopt with `error` set.
std::optional<std::string> CreateLlvmpipeContext(std::optional<int> lp_threads, std::string& error);

// Compiles `vertex_source` (GLSL ES, its #version on the first line) with an empty fragment shader of
// the same version, and links them capturing `varyings` interleaved. The program object, or 0 with
// `error` holding the info log.
unsigned LinkTransformFeedbackProgram(const std::string& vertex_source, const std::vector<std::string>& varyings,
                                      std::string& error);

// Links `program` (its shaders attached, then deleted): the program, or 0 with `error` = "WHAT does
// not link: LOG" and the program deleted.
unsigned LinkAttachedProgram(unsigned program, const char* what, std::string& error);

// Compiles `source` as a shader of `kind` (GL_VERTEX_SHADER, GL_COMPUTE_SHADER, ...): the shader
// object, or 0 with `error` holding the info log.
unsigned CompileShader(unsigned kind, const std::string& source, std::string& error);

// glGetError as text: true when there is none, else false with `error` = "WHAT: GL error 0x....".
bool GlOk(const char* what, std::string& error);

// The first `count` floats of GL buffer `buffer`, mapped for reading (through GL_COPY_READ_BUFFER, so
// no other binding changes); waits for the commands that write it. A compute pass's stores need a
// glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT) first. nullopt with `error` set where GL fails.
std::optional<std::vector<float>> ReadBufferFloats(unsigned buffer, std::size_t count, std::string& error);

// One vertex attribute: `components` floats per vertex, vertex after vertex, at `location`.
struct GlAttribute {
  int location = 0;
  int components = 4;
  std::vector<float> data;
};

// A linked program with its inputs in buffers and a transform-feedback buffer for its outputs
// (`varyings`, interleaved, `output_floats` floats per vertex).
class TransformFeedbackRun {
 public:
  // Compiles and links; nullopt with `error` holding the info log on failure. Each draw runs
  // `vertex_count` vertices; 0 takes the count from the attributes (a shader that reads no attribute
  // needs it given).
  static std::unique_ptr<TransformFeedbackRun> Create(const std::string& vertex_source,
                                                      const std::vector<std::string>& varyings, int output_floats,
                                                      const std::vector<GlAttribute>& attributes,
                                                      const std::vector<float>& constants, std::string& error,
                                                      std::size_t vertex_count = 0);
  ~TransformFeedbackRun();
  TransformFeedbackRun(const TransformFeedbackRun&) = delete;
  TransformFeedbackRun& operator=(const TransformFeedbackRun&) = delete;

  // Issues `draws` draws of every vertex, then waits for them (glFinish). False with `error` set
  // when GL reports an error.
  bool Draw(int draws, std::string& error);
  // Draws once, checks that every vertex reached the buffer, and returns the outputs (output_floats
  // per vertex); nullopt with `error` set otherwise.
  std::optional<std::vector<float>> DrawAndRead(std::string& error);

 private:
  TransformFeedbackRun() = default;
  unsigned program_ = 0, vertex_array_ = 0, output_buffer_ = 0, query_ = 0;
  std::vector<unsigned> input_buffers_;
  std::size_t vertex_count_ = 0;
  int output_floats_ = 0;
};

}  // namespace vs11::gl
