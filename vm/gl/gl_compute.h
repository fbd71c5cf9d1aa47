// A program's compute translation (vm/translate/compute_interface.h) on an OpenGL ES 3.1 context: the
// gl engine's compute path (gl_compute_engine.cc), the tests' interleaved and large runs, the
// llvmpipe benchmark, and GPU passes that hand it buffers of their own (a constant buffer another
// compute pass wrote: BindConstantBuffer). Every call needs the context it was created on current.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "vm/core/machine.h"
#include "vm/core/program.h"
#include "vm/core/result.h"
#include "vm/translate/compute_interface.h"
#include "vm/translate/translate.h"

namespace vs11::gl {

class GlContext;

// Whether `context` is OpenGL ES 3.1 or later, which has compute shaders and storage buffers.
bool OffersCompute(const GlContext& context);

// The compute translation the gl engine runs for `options`: GlTranslateOptions' (exact_on_driver, the
// float rules, the bank's size) as a compute shader in GLSL ES 3.20 on an ES 3.2 context (`precise`
// outputs), else GLSL ES 3.10.
translate::TranslateOptions GlComputeTranslateOptions(const EngineOptions& options, int constant_count, bool es32);

// Compiles and links the compute shader `source` (GLSL ES 3.10 or later, its #version first): the
// program object, or an error (kGlCompile) holding the compiler's or linker's log.
Result<unsigned> LinkComputeProgram(const std::string& source);

class ComputeRun {
 public:
  // Compiles and links `compute_source` (a compute translation, its #version first); an error holding
  // the info log where it does not compile or link.
  static Result<std::unique_ptr<ComputeRun>> Create(const std::string& compute_source);
  // The translation of `program` under `options` (options.stage must be Stage::kCompute).
  static Result<std::unique_ptr<ComputeRun>> Create(const Program& program,
                                                    const translate::TranslateOptions& options);
  ~ComputeRun();
  ComputeRun(const ComputeRun&) = delete;
  ComputeRun& operator=(const ComputeRun&) = delete;

  // The constant bank from a GL buffer that already holds it (std140 vec4 c[N], 16 bytes a row,
  // from byte `offset`, which must be a multiple of GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT): nothing is
  // copied, and what a pass writes there before the next Dispatch is what that Dispatch reads. The
  // buffer stays the caller's; it must hold `rows` vec4s from `offset` and outlive its use here.
  void BindConstantBuffer(unsigned buffer, std::size_t offset, int rows);
  // The bank from memory (N rows of 4 floats) into a buffer of the run's own, and bound as above.
  Status SetConstants(const std::vector<float>& rows);

  // Runs the program over `vertex_count` vertices, reading `input_buffer` and writing `output_buffer`
  // (GL buffer names) where `layout` says (its vertex_count is set here), in one dispatch of as many
  // work groups as the count needs, in two dimensions past max_groups_x(). Returns without waiting;
  // storage written is visible to buffer reads and mapping that follow (a memory barrier is issued).
  // An error (kGlError) where GL reports one.
  Status Dispatch(translate::ComputeLayoutBlock layout, unsigned input_buffer, unsigned output_buffer,
                  std::size_t vertex_count);

  // Work groups along x at most: the driver's GL_MAX_COMPUTE_WORK_GROUP_COUNT[0] unless lowered (the
  // tests lower it to dispatch in two dimensions at small counts).
  std::uint32_t max_groups_x() const { return max_groups_x_; }
  void set_max_groups_x(std::uint32_t groups) { max_groups_x_ = groups; }

 private:
  ComputeRun() = default;
  unsigned program_ = 0, layout_buffer_ = 0, constants_buffer_ = 0;
  unsigned bound_constants_ = 0;  // the buffer Dispatch binds: constants_buffer_ or the caller's
  std::size_t bound_offset_ = 0, bound_rows_ = 0;
  std::uint32_t max_groups_x_ = 65535;
};

}  // namespace vs11::gl
