// Vertex shaders run over vertex buffers with transform feedback and GL_RASTERIZER_DISCARD, on an
// OpenGL ES 3.0 context (gl_context.h): the translator's tests and bench/compare_llvmpipe.
#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "vm/core/machine.h"
#include "vm/core/result.h"

namespace vs11::gl {

// Creates a context on Mesa's llvmpipe (GlContext::Create(nullopt)) that stays current on the calling
// thread for the rest of the process. `lp_threads`, when set, goes to LP_NUM_THREADS, which Mesa reads
// when the display is initialised (so only the process's first display honours it). Returns
// GL_RENDERER.
Result<std::string> CreateLlvmpipeContext(std::optional<int> lp_threads);

// Compiles `vertex_source` (GLSL ES, its #version on the first line) with an empty fragment shader of
// the same version, and links them capturing `varyings` interleaved. The program object, or an error
// (kGlCompile) holding the info log.
Result<unsigned> LinkTransformFeedbackProgram(const std::string& vertex_source,
                                              const std::vector<std::string>& varyings);

// Links `program` (its shaders attached, then deleted): the program, or an error (kGlCompile) "WHAT does
// not link: LOG" with the program deleted.
Result<unsigned> LinkAttachedProgram(unsigned program, const char* what);

// Compiles `source` as a shader of `kind` (GL_VERTEX_SHADER, GL_COMPUTE_SHADER, ...): the shader
// object, or an error (kGlCompile) holding the info log.
Result<unsigned> CompileShader(unsigned kind, const std::string& source);

// glGetError as a Status: an error (kGlError) "WHAT: GL error 0x...." where GL reports one.
Status GlOk(const char* what);

// The first `count` floats of GL buffer `buffer`, mapped for reading (through GL_COPY_READ_BUFFER, so
// no other binding changes); waits for the commands that write it. A compute pass's stores need a
// glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT) first. An error (kGlError) where GL fails.
Result<std::vector<float>> ReadBufferFloats(unsigned buffer, std::size_t count);

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
  // Compiles and links; an error holding the info log on failure. Each draw runs `vertex_count`
  // vertices; 0 takes the count from the attributes (a shader that reads no attribute needs it given).
  static Result<std::unique_ptr<TransformFeedbackRun>> Create(
      const std::string& vertex_source, const std::vector<std::string>& varyings, int output_floats,
      const std::vector<GlAttribute>& attributes, const std::vector<float>& constants, std::size_t vertex_count = 0);
  ~TransformFeedbackRun();
  TransformFeedbackRun(const TransformFeedbackRun&) = delete;
  TransformFeedbackRun& operator=(const TransformFeedbackRun&) = delete;

  // Issues `draws` draws of every vertex, then waits for them (glFinish). An error when GL reports one.
  Status Draw(int draws);
  // Draws once, checks that every vertex reached the buffer, and returns the outputs (output_floats
  // per vertex).
  Result<std::vector<float>> DrawAndRead();

 private:
  TransformFeedbackRun() = default;
  unsigned program_ = 0, vertex_array_ = 0, output_buffer_ = 0, query_ = 0;
  std::vector<unsigned> input_buffers_;
  std::size_t vertex_count_ = 0;
  int output_floats_ = 0;
};

}  // namespace vs11::gl
