#include "irradiance/gpu/gpu_frame.h"

#include <GLES3/gl31.h>

#include <algorithm>
#include <bit>
#include <cassert>
#include <cmath>

#include <fmt/format.h>

#include "irradiance/gpu/frame_shaders.h"
#include "irradiance/sh/projection_kernels.h"
#include "vm/gl/gl_compute.h"
#include "vm/gl/gl_runner.h"

namespace vs11::irradiance::gpu {
namespace {

using vs11::gl::GlOk;
using vs11::gl::LinkComputeProgram;
using vs11::gl::ScopedCurrent;

// Texels a thread of the projection sums on its own, about: longer runs cost accuracy
// (GpuProjectionErrorFactor), shorter ones more partials.
constexpr int kTexelsPerThread = 16;
constexpr int kMaxGroupsPerFace = 256;
constexpr double kUnitRoundoff = 0x1p-24;

// Level 0's nine block moments of a face of `size` (the same on every face), moment-major, formed
// in double from each texel's exact solid angle and centre and rounded to float once: what
// BasisLevel holds for the coarser levels (kernels::kBlockMomentSlots).
std::vector<float> FinestBlockMoments(int size) {
  const std::size_t texels = static_cast<std::size_t>(size) * size;
  std::vector<float> moments(kernels::kBlockMoments * texels);
  for (int y = 0; y < size; ++y) {
    const double t = 2.0 * (y + 0.5) / size - 1.0;
    for (int x = 0; x < size; ++x) {
      const double s = 2.0 * (x + 0.5) / size - 1.0;
      const double q = TexelSolidAngle(x, y, size);
      const double r = 1.0 / std::sqrt(1.0 + s * s + t * t);
      for (int j = 0; j < kernels::kBlockMoments; ++j) {
        const kernels::BlockMomentSlot slot = kernels::kBlockMomentSlots[j];
        const double value = q * std::pow(r, kernels::kMomentPowerOfR[slot.moment]) *
                             std::pow(s, kernels::kMomentPowerOfS[slot.moment]) * std::pow(t, slot.power_of_t);
        moments[j * texels + static_cast<std::size_t>(y) * size + x] = static_cast<float>(value);
      }
    }
  }
  return moments;
}

}  // namespace

std::vector<float> LevelBlockMoments(const BasisPyramid& basis, int level) {
  const int size = basis.face_size >> level;
  if (level == 0) return FinestBlockMoments(size);
  const BasisLevel& weights = basis.levels[static_cast<std::size_t>(level)];
  std::vector<float> moments;
  for (const std::vector<float>& slot : weights.weights) moments.insert(moments.end(), slot.begin(), slot.end());
  return moments;
}

namespace {

std::vector<float> CombinationFloats() {
  const BlockMomentCombination combination = BlockMomentCombinationFactors();
  std::vector<float> floats;
  for (const auto& face : combination) {
    for (const auto& row : face) {
      for (double factor : row) floats.push_back(static_cast<float>(factor));
    }
  }
  return floats;
}

GLuint StorageBuffer(std::size_t bytes, const void* data) {
  GLuint buffer = 0;
  glGenBuffers(1, &buffer);
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffer);
  glBufferData(GL_SHADER_STORAGE_BUFFER, static_cast<GLsizeiptr>(bytes), data, GL_DYNAMIC_COPY);
  return buffer;
}

// `count` floats of a storage buffer a compute pass wrote.
Result<std::vector<float>> ReadFloats(GLuint buffer, std::size_t count) {
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  return vs11::gl::ReadBufferFloats(buffer, count);
}

}  // namespace

int ProjectionGroupsPerFace(int size) {
  const long texels = static_cast<long>(size) * size;
  const long per_group = static_cast<long>(kReductionThreads) * kTexelsPerThread;
  return static_cast<int>(std::clamp<long>((texels + per_group - 1) / per_group, 1, kMaxGroupsPerFace));
}

double GpuProjectionErrorFactor(int face_size, int level) {
  const int size = face_size >> level;
  const long groups = ProjectionGroupsPerFace(size);
  const long texels = static_cast<long>(size) * size;
  const long per_thread = (texels + groups * kReductionThreads - 1) / (groups * kReductionThreads);
  const int mip_levels = level;
  const long tree = std::countr_zero(static_cast<unsigned>(kReductionThreads));
  const long combination = 9 * 6 + 1;
  const long gpu = 3L * mip_levels + 1 + per_thread + tree + groups + combination;
  const long cpu = 5 + 16 + 3;
  auto gamma = [](long n) { return n * kUnitRoundoff / (1.0 - n * kUnitRoundoff); };
  return gamma(gpu) + gamma(cpu);
}

Result<std::unique_ptr<GpuFrame>> GpuFrame::Create(std::optional<int> device, const BasisPyramid& basis, int level,
                                                   int constant_count, int constant_base) {
  assert(level >= 0 && level < static_cast<int>(basis.levels.size()));
  assert(constant_base >= 0 && constant_base + 7 <= constant_count);
  std::unique_ptr<GpuFrame> frame(new GpuFrame());
  Result<std::unique_ptr<vs11::gl::GlContext>> context = vs11::gl::GlContext::Create(device);
  if (!context) return context.error();
  frame->context_ = std::move(context).value();
  if (!vs11::gl::OffersCompute(*frame->context_)) {
    return Failure(DiagnosticCode::kGlUnavailable,
                   fmt::format("'{}' offers '{}', not OpenGL ES 3.1 (compute shaders)", frame->context_->renderer(),
                               frame->context_->version()));
  }
  frame->face_size_ = basis.face_size;
  frame->level_ = level;
  frame->constant_count_ = constant_count;
  frame->constant_base_ = constant_base;
  ScopedCurrent current(*frame->context_);
  if (!current.ok()) return current.status().error();
  if (Status built = frame->Build(basis); !built) return built.error();
  return frame;
}

Status GpuFrame::Build(const BasisPyramid& basis) {
  for (auto [program, source] : {std::pair{&mip_program_, MipShaderSource()},
                                 std::pair{&projection_program_, ProjectionShaderSource()},
                                 std::pair{&coefficients_program_, CoefficientsShaderSource()}}) {
    const Result<unsigned> linked = LinkComputeProgram(source);
    if (!linked) return linked.error();
    *program = *linked;
  }

  glGenTextures(1, &texture_);
  glBindTexture(GL_TEXTURE_CUBE_MAP, texture_);
  // Levels down to the chosen one: the projection reads no coarser one.
  glTexStorage2D(GL_TEXTURE_CUBE_MAP, level_ + 1, GL_RGBA32F, face_size_, face_size_);
  const int size = face_size_ >> level_;
  groups_ = ProjectionGroupsPerFace(size);
  const std::vector<float> moments = LevelBlockMoments(basis, level_);
  moments_ = StorageBuffer(moments.size() * sizeof(float), moments.data());
  partials_ = StorageBuffer(static_cast<std::size_t>(kCubeFaceCount) * groups_ * kFaceSums * sizeof(float), nullptr);
  const std::vector<float> combination = CombinationFloats();
  combination_ = StorageBuffer(combination.size() * sizeof(float), combination.data());
  coefficients_ = StorageBuffer(kSh9Coefficients * 3 * sizeof(float), nullptr);
  const std::vector<float> zeros(static_cast<std::size_t>(constant_count_) * 4, 0.0f);
  bank_ = StorageBuffer(zeros.size() * sizeof(float), zeros.data());

  glUseProgram(coefficients_program_);
  glUniform1i(glGetUniformLocation(coefficients_program_, "groups"), groups_);
  glUniform4f(glGetUniformLocation(coefficients_program_, "c"), static_cast<float>(kShC0), static_cast<float>(kShC1),
              static_cast<float>(kShC2), static_cast<float>(3.0 * kShC3));
  glUniform1f(glGetUniformLocation(coefficients_program_, "c3"), static_cast<float>(kShC3));
  glUniform1f(glGetUniformLocation(coefficients_program_, "c4"), static_cast<float>(kShC4));
  glUniform1i(glGetUniformLocation(coefficients_program_, "constant_base"), constant_base_);
  glUseProgram(projection_program_);
  glUniform1i(glGetUniformLocation(projection_program_, "size"), size);
  return GlOk("creating the frame's texture and buffers");
}

GpuFrame::~GpuFrame() {
  if (!context_) return;
  ScopedCurrent current(*context_);
  if (!current.ok()) return;
  const GLuint buffers[] = {moments_, partials_, combination_, coefficients_, bank_};
  glDeleteBuffers(5, buffers);
  glDeleteTextures(1, &texture_);
  glDeleteProgram(mip_program_);
  glDeleteProgram(projection_program_);
  glDeleteProgram(coefficients_program_);
}

Status GpuFrame::Upload(const CubeMap& environment) {
  assert(environment.face_size == face_size_);
  ScopedCurrent current(*context_);
  if (!current.ok()) return current.status();
  glBindTexture(GL_TEXTURE_CUBE_MAP, texture_);
  staging_.resize(static_cast<std::size_t>(face_size_) * face_size_ * 4);
  for (int f = 0; f < kCubeFaceCount; ++f) {
    const std::vector<glm::vec3>& pixels = environment.faces[static_cast<std::size_t>(f)].pixels;
    for (std::size_t i = 0; i < pixels.size(); ++i) {
      staging_[4 * i] = pixels[i].r;
      staging_[4 * i + 1] = pixels[i].g;
      staging_[4 * i + 2] = pixels[i].b;
      staging_[4 * i + 3] = 1.0f;
    }
    glTexSubImage2D(static_cast<GLenum>(GL_TEXTURE_CUBE_MAP_POSITIVE_X + f), 0, 0, 0, face_size_, face_size_, GL_RGBA,
                    GL_FLOAT, staging_.data());
  }
  return GlOk("uploading the environment");
}

Status GpuFrame::Project() {
  ScopedCurrent current(*context_);
  if (!current.ok()) return current.status();
  glUseProgram(mip_program_);
  const GLint coarse_size = glGetUniformLocation(mip_program_, "coarse_size");
  for (int k = 1; k <= level_; ++k) {
    const int size = face_size_ >> k;
    glBindImageTexture(0, texture_, k - 1, GL_TRUE, 0, GL_READ_ONLY, GL_RGBA32F);
    glBindImageTexture(1, texture_, k, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    glUniform1i(coarse_size, size);
    const auto tiles = static_cast<GLuint>((size + kMipTile - 1) / kMipTile);
    glDispatchCompute(tiles, tiles, kCubeFaceCount);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  }
  glUseProgram(projection_program_);
  glBindImageTexture(0, texture_, level_, GL_TRUE, 0, GL_READ_ONLY, GL_RGBA32F);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, moments_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, partials_);
  glDispatchCompute(static_cast<GLuint>(groups_), 1, kCubeFaceCount);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  glUseProgram(coefficients_program_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, combination_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, coefficients_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, bank_);
  glDispatchCompute(1, 1, 1);
  // The program stage reads the bank as its uniform block, a later read-back as a mapped buffer.
  glMemoryBarrier(GL_UNIFORM_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
  return GlOk("projecting on the GPU");
}

Status GpuFrame::Finish() {
  ScopedCurrent current(*context_);
  if (!current.ok()) return current.status();
  glFinish();
  return GlOk("finishing the frame");
}

Result<Sh9Rgb> GpuFrame::ReadCoefficients() {
  ScopedCurrent current(*context_);
  if (!current.ok()) return current.status().error();
  const Result<std::vector<float>> floats = ReadFloats(coefficients_, kSh9Coefficients * 3);
  if (!floats) return floats.error();
  Sh9Rgb sh;
  for (int lm = 0; lm < kSh9Coefficients; ++lm) {
    for (int c = 0; c < 3; ++c) sh.coefficients[lm][c] = (*floats)[static_cast<std::size_t>(lm * 3 + c)];
  }
  return sh;
}

Result<SevenConstants> GpuFrame::ReadConstants() {
  ScopedCurrent current(*context_);
  if (!current.ok()) return current.status().error();
  const Result<std::vector<float>> floats = ReadFloats(bank_, static_cast<std::size_t>(constant_count_) * 4);
  if (!floats) return floats.error();
  SevenConstants constants;
  for (int r = 0; r < 7; ++r) {
    for (int c = 0; c < 4; ++c) {
      constants.registers[static_cast<std::size_t>(r)][c] = (*floats)[static_cast<std::size_t>((constant_base_ + r) * 4 + c)];
    }
  }
  return constants;
}

}  // namespace vs11::irradiance::gpu
