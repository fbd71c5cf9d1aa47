// Stage 5 of the GPU frame (gpu_frame.h): the vs_1_1 program over the vertices, its constants read
// from the frame's bank buffer where the coefficients stage wrote them, so they never pass through
// the CPU. The program runs as the gl engine's translation (vm/translate, GlTranslateOptions) through
// transform feedback, with its `uniform vec4 c[N]` declared as a std140 uniform block instead, bound
// to that buffer. (The compute-shader translation of issue 34 section 1 takes its place once it
// binds a constant buffer already on the GPU.)
#pragma once

#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "irradiance/gpu/gpu_frame.h"
#include "irradiance/report/paper_program.h"

namespace vs11::irradiance::gpu {

class ProgramStage {
 public:
  // Links `program` for `frame`'s context and bank, with `normals` as (x, y, z, 1) in its normal
  // register, uploaded once. Null with `error` set when the translation does not link.
  static std::unique_ptr<ProgramStage> Create(GpuFrame& frame, const PaperProgram& program,
                                              std::span<const glm::vec3> normals, std::string& error);
  ~ProgramStage();
  ProgramStage(const ProgramStage&) = delete;
  ProgramStage& operator=(const ProgramStage&) = delete;

  // Runs the program over every vertex with the bank as it is now; queued, not waited for.
  bool Run(std::string& error);
  // The output register's rgb per vertex, after Run.
  std::optional<std::vector<glm::vec3>> Read(std::string& error);
  std::size_t vertex_count() const { return vertex_count_; }

 private:
  explicit ProgramStage(GpuFrame& frame) : frame_(frame) {}
  GpuFrame& frame_;
  unsigned program_ = 0, vertex_array_ = 0, input_ = 0, output_ = 0;
  int output_components_ = 4;
  std::size_t vertex_count_ = 0;
};

// `translation` (a GLSL ES translation of vm/translate) with its constant bank `uniform vec4 c[N];`
// as `layout(std140) uniform Vs11Constants { vec4 c[N]; };`; nullopt when it declares no bank.
std::optional<std::string> WithUniformBlockBank(const std::string& translation);

}  // namespace vs11::irradiance::gpu
