// Stage 5 of the GPU frame (gpu_frame.h): the vs_1_1 program over the vertices, its constants read
// from the frame's bank buffer where the coefficients stage wrote them, so they never pass through
// the CPU. The program runs as the gl engine's compute translation (vm/gl/gl_compute.h, the options
// of GlComputeTranslateOptions) over storage buffers, with the bank bound as it lies on the GPU
// (ComputeRun::BindConstantBuffer).
#pragma once

#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "irradiance/gpu/gpu_frame.h"
#include "irradiance/report/paper_program.h"
#include "vm/gl/gl_compute.h"

namespace vs11::irradiance::gpu {

class ProgramStage {
 public:
  // Links `program` for `frame`'s context and bank, with `normals` as (x, y, z, 1) in its normal
  // register, uploaded once. An error (kGlCompile) when the translation does not link.
  static Result<std::unique_ptr<ProgramStage>> Create(GpuFrame& frame, const PaperProgram& program,
                                                      std::span<const glm::vec3> normals);
  ~ProgramStage();
  ProgramStage(const ProgramStage&) = delete;
  ProgramStage& operator=(const ProgramStage&) = delete;

  // Runs the program over every vertex with the bank as it is now; queued, not waited for.
  Status Run();
  // The output register's rgb per vertex, after Run.
  Result<std::vector<glm::vec3>> Read();
  std::size_t vertex_count() const { return vertex_count_; }

 private:
  explicit ProgramStage(GpuFrame& frame) : frame_(frame) {}
  GpuFrame& frame_;
  std::unique_ptr<vs11::gl::ComputeRun> run_;
  translate::ComputeLayoutBlock layout_;
  unsigned input_ = 0, output_ = 0;
  std::size_t vertex_count_ = 0;
};

}  // namespace vs11::irradiance::gpu
