// The paper's dynamic-lighting frame (section 3.3 steps 2-5) on a GPU through OpenGL ES 3.1 compute
// shaders, with nothing read back to the CPU between the stages:
//
//   environment (CPU, changes every frame) ─upload─> cube texture rgba32f, level 0
//     ─mips─> its levels 1.. in the same texture (2 x 2 float means, irradiance/sh's order)
//     ─projection─> per workgroup: 27 sums of radiance x block moment per face (the basis pyramid's
//                   nine moments of the chosen level, irradiance/sh/sh_projection.h, uploaded once)
//     ─coefficients─> one workgroup: the faces' sums, the nine RGB coefficients and the seven
//                     constants of Table 1, written into a constant bank buffer
//     ─program─> the vs_1_1 program's compute translation over the vertices, reading that buffer
//                as its constants (program_stage.h)
//
// Coefficients, constants and the program's outputs can be read back once a frame is done (for
// tests and irrmap); a frame benchmark reads nothing back.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "irradiance/io/cube_map.h"
#include "irradiance/sh/sh9.h"
#include "irradiance/sh/sh_projection.h"
#include "vm/core/result.h"
#include "vm/gl/gl_context.h"

namespace vs11::irradiance::gpu {

// The frame's GL objects for one face size and one level; the context is current on the calling
// thread during every call (each makes it so, as vm/gl's engine does).
class GpuFrame {
 public:
  // A context on `device` (vm/gl's ListGlDevices index; nullopt: Mesa's llvmpipe), the shaders, the
  // cube texture of `basis.face_size` with every mip level, and `level`'s nine block moments from
  // `basis` (level 0's formed here in double) uploaded once. `constant_count`: the vec4s of the bank
  // buffer, `constant_base`: where Table 1's seven registers go in it. An error where no OpenGL ES
  // 3.1 context can be had (kGlUnavailable) or a shader does not build (kGlCompile). 0 <= level < basis.levels.size().
  static Result<std::unique_ptr<GpuFrame>> Create(std::optional<int> device, const BasisPyramid& basis, int level,
                                                  int constant_count, int constant_base);
  ~GpuFrame();
  GpuFrame(const GpuFrame&) = delete;
  GpuFrame& operator=(const GpuFrame&) = delete;

  // Stage 1: level 0 of the cube texture from `environment` (face size basis.face_size, asserted).
  Status Upload(const CubeMap& environment);
  // Stages 2-4: the mips down to the level, the projection and the constants; queued, not waited for.
  Status Project();
  // Waits for everything queued (glFinish): a frame's end in the benchmark.
  Status Finish();

  // Read-backs, after Project: the nine coefficients (float, as the GPU summed them) and Table 1.
  Result<Sh9Rgb> ReadCoefficients();
  Result<SevenConstants> ReadConstants();

  vs11::gl::GlContext& context() { return *context_; }
  unsigned constant_buffer() const { return bank_; }  // the bank, std140/std430 vec4 per register
  int constant_count() const { return constant_count_; }
  int level() const { return level_; }
  int groups_per_face() const { return groups_; }
  int face_size() const { return face_size_; }

 private:
  GpuFrame() = default;
  Status Build(const BasisPyramid& basis);

  std::unique_ptr<vs11::gl::GlContext> context_;
  int face_size_ = 0, level_ = 0, groups_ = 1, constant_count_ = 0, constant_base_ = 0;
  unsigned mip_program_ = 0, projection_program_ = 0, coefficients_program_ = 0;
  unsigned texture_ = 0, moments_ = 0, partials_ = 0, combination_ = 0, coefficients_ = 0, bank_ = 0;
  std::vector<float> staging_;  // rgba rows of one face for the upload
};

// The nine block moments of `level` (kernels::kBlockMomentSlots order, moment-major: moment j of
// texel i of a face at j * size^2 + i, the same on every face) that the projection weights radiance
// with: the basis pyramid's for the coarse levels, level 0's formed in double from each texel's exact
// solid angle and centre and rounded to float once.
std::vector<float> LevelBlockMoments(const BasisPyramid& basis, int level);

// Workgroups per face of the projection's first pass for faces of `size` at the chosen level: about
// 16 texels a thread, at most 256 groups.
int ProjectionGroupsPerFace(int size);

// The bound of the GPU's coefficients against irradiance/sh's ProjectLevel of the same map and level,
// as a multiple of B_lm,c = sum over faces and moments j of |BlockMomentCombinationFactors[f][lm][j]|
// x sum over texels of |L_c x moment_j| (the sum of the absolute values of every term). With
// u = 2^-24, a float sum of n terms is within gamma_n = n u / (1 - n u) of the exact sum times the
// sum of its absolute terms (Higham, Accuracy and Stability of Numerical Algorithms, 4.2), and a term
// that passes through d roundings on its way to the result carries at most gamma_d of itself. The
// GPU's longest chain: 3 roundings per mip level above `level` (if the driver reorders the mean),
// 1 for the product, the running sum of ceil(size^2 / (groups x 128)) texels a thread, log2(128) = 7
// in the workgroup's tree, `groups` in the second pass, 9 x 6 + 1 in the combination with the factors
// rounded to float. The CPU's ProjectLevel: at most 5 roundings forming a term, 16 float additions per
// lane, then double: gamma_24 more (and level 0's moments formed differently: within those 5).
double GpuProjectionErrorFactor(int face_size, int level);

}  // namespace vs11::irradiance::gpu
