// Direct and mip-pyramid SH9 projection of cube environment maps. See sh_projection.h.
#include "irradiance/sh/sh_projection.h"

#include <algorithm>
#include <cmath>
#include <cassert>
#include <cstddef>
#include <cstring>
#include <mutex>

#include "irradiance/io/cube_map.h"
#include "irradiance/sh/projection_kernels.h"
#include "irradiance/sh/row_sum_kernels.h"

namespace vs11::irradiance {
namespace {

// Solid angles of the texels of row y (the same on every face).
void RowSolidAngles(int y, int size, std::vector<double>& out) {
  out.resize(size);
  for (int x = 0; x < size; ++x) out[x] = TexelSolidAngle(x, y, size);
}

// Adds one face row's products basis * radiance * solid angle (radiance from `row`) into `sums`.
void AccumulateDirectRow(CubeFace face, int y, int size, const glm::vec3* row,
                         const std::vector<double>& solid_angles,
                         std::array<glm::dvec3, kSh9Coefficients>& sums) {
  std::array<glm::dvec3, kSh9Coefficients> row_sums{};
  for (int x = 0; x < size; ++x) {
    const std::array<double, kSh9Coefficients> basis = ShBasis(TexelDirection(face, x, y, size));
    const glm::dvec3 weighted = glm::dvec3(row[x]) * solid_angles[x];
    for (int i = 0; i < kSh9Coefficients; ++i) row_sums[i] += basis[i] * weighted;
  }
  for (int i = 0; i < kSh9Coefficients; ++i) sums[i] += row_sums[i];
}

std::size_t LevelTexels(int size) {
  return static_cast<std::size_t>(kCubeFaceCount) * size * size;
}

// True when chain.levels are LevelCount(face_size) cube maps of faces face_size >> k.
bool HasPyramidShape(const CubeMipChain& chain, int face_size) {
  if (static_cast<int>(chain.levels.size()) != LevelCount(face_size)) return false;
  for (std::size_t k = 0; k < chain.levels.size(); ++k) {
    const int size = face_size >> k;
    if (chain.levels[k].face_size != size) return false;
    for (const Image& face : chain.levels[k].faces) {
      if (face.width != size || face.height != size) return false;
    }
  }
  return true;
}

static_assert(sizeof(glm::vec3) == 3 * sizeof(float), "kernels read rows of texels as interleaved floats");
const float* PixelFloats(const Image& image, int y) { return &image.at(0, y).x; }
float* PixelFloats(Image& image, int y) { return &image.at(0, y).x; }

// Each texel of `coarse` (half the size of `fine`) becomes the float mean of its 2 x 2 children.
void HalveFace(const Image& fine, Image& coarse) {
  for (int y = 0; y < coarse.height; ++y) {
    kernels::HalveRowPair(PixelFloats(fine, 2 * y), PixelFloats(fine, 2 * y + 1), PixelFloats(coarse, y),
                          coarse.width);
  }
}

// Levels 2.. of face f of a chain already shaped as a pyramid, from its level 1. Level by level
// within one face: a face's level 1 (a twelfth of level 0's bytes) is still in cache.
void FillLevelsFromTwo(CubeMipChain& chain, int f) {
  for (std::size_t k = 2; k < chain.levels.size(); ++k) HalveFace(chain.levels[k - 1].faces[f], chain.levels[k].faces[f]);
}

// Levels 1.. of a chain already shaped as a pyramid, from its level 0.
void FillCoarserLevels(CubeMipChain& chain) {
  if (chain.levels.size() < 2) return;
  for (int f = 0; f < kCubeFaceCount; ++f) {
    HalveFace(chain.levels[0].faces[f], chain.levels[1].faces[f]);
    FillLevelsFromTwo(chain, f);
  }
}

// The face coordinate (s or t) of the centre of texel `i` of `size`, as in TexelDirection.
double FaceCoordinate(int i, int size) { return 2.0 * (i + 0.5) / size - 1.0; }

// Direction of a texel of `face` at (s, t), before normalisation, as e(t) + s beta with
// e(t) = alpha + t gamma: each component of FaceDirection is linear in 1, s and t.
struct FaceLinearForm {
  glm::dvec3 alpha, beta, gamma;
};

FaceLinearForm LinearFormOf(CubeFace face) {
  const glm::dvec3 alpha = FaceDirection(face, 0.0, 0.0);
  return {alpha, FaceDirection(face, 1.0, 0.0) - alpha, FaceDirection(face, 0.0, 1.0) - alpha};
}

// Adds one face's contribution to the nine coefficients from its moments (CubeMoments). With
// e(t) = alpha + t gamma, the unit direction is r (e + s beta): q y_lm is q times a constant, q r
// times a linear form in s, or q r^2 times a quadratic form in s, whose factors are polynomials in
// t, matched here with the moments' sums over rows weighted by 1, t and t^2.
void AddFaceFromMoments(const kernels::FaceMomentSums& m, const FaceLinearForm& form,
                        std::array<glm::dvec3, kSh9Coefficients>& sums) {
  const glm::dvec3 a = form.alpha, b = form.beta, g = form.gamma;
  auto moment = [&](int power, int k) { return glm::dvec3(m[power][3 * k], m[power][3 * k + 1], m[power][3 * k + 2]); };
  const glm::dvec3 q = moment(0, 0);
  auto linear = [&](int i) { return a[i] * moment(0, 1) + g[i] * moment(1, 1) + b[i] * moment(0, 2); };
  // sum L q r^2 s^2 = sum L q - (1 + t^2) sum L q r^2, since r^2 (1 + s^2 + t^2) = 1.
  const glm::dvec3 qr2ss = moment(0, 0) - moment(0, 3) - moment(2, 3);
  auto quadratic = [&](int i, int j) {
    return a[i] * a[j] * moment(0, 3) + (a[i] * g[j] + g[i] * a[j]) * moment(1, 3) + g[i] * g[j] * moment(2, 3) +
           (a[i] * b[j] + b[i] * a[j]) * moment(0, 4) + (g[i] * b[j] + b[i] * g[j]) * moment(1, 4) +
           b[i] * b[j] * qr2ss;
  };
  sums[ShIndex(0, 0)] += kShN0 * q;
  sums[ShIndex(1, -1)] += kShN1 * linear(1);
  sums[ShIndex(1, 0)] += kShN1 * linear(2);
  sums[ShIndex(1, 1)] += kShN1 * linear(0);
  sums[ShIndex(2, -2)] += kShN2 * quadratic(0, 1);
  sums[ShIndex(2, -1)] += kShN2 * quadratic(1, 2);
  sums[ShIndex(2, 0)] += kShN3 * (3.0 * quadratic(2, 2) - q);
  sums[ShIndex(2, 1)] += kShN2 * quadratic(0, 2);
  sums[ShIndex(2, 2)] += kShN4 * (quadratic(0, 0) - quadratic(1, 1));
}

// The finest level's per-texel weights of one face (see FinestWeights), from its solid angles.
FinestWeights MakeFinestWeights(const std::vector<double>& solid_angles, int size) {
  FinestWeights weights;
  weights.q.resize(solid_angles.size());
  weights.qr.resize(solid_angles.size());
  weights.qr2.resize(solid_angles.size());
  for (int y = 0; y < size; ++y) {
    const double t = FaceCoordinate(y, size);
    for (int x = 0; x < size; ++x) {
      const double s = FaceCoordinate(x, size);
      const std::size_t i = static_cast<std::size_t>(y) * size + x;
      const double r2 = 1.0 / (1.0 + s * s + t * t);
      weights.q[i] = static_cast<float>(solid_angles[i]);
      weights.qr[i] = static_cast<float>(solid_angles[i] * std::sqrt(r2));
      weights.qr2[i] = static_cast<float>(solid_angles[i] * r2);
    }
  }
  return weights;
}

// Face f of levels 1.. of `pyramid` (already sized). Level 0 is computed in double and summed (in
// double) into its parents; every coarser level is then the double sum of its four
// double children, rounded to float once. The double sums of one face take 18 bytes per texel of
// it (a sixth of a whole level 1).
void BuildBasisFace(int f, const std::vector<double>& solid_angles, BasisPyramid& pyramid) {
  const int face_size = pyramid.face_size;
  const int count = static_cast<int>(pyramid.levels.size());
  std::array<std::vector<double>, kSh9Coefficients> parent;
  const CubeFace face = kAllCubeFaces[f];
  const int parent_size = face_size / 2;
  for (auto& p : parent) p.assign(static_cast<std::size_t>(parent_size) * parent_size, 0.0);
  for (int y = 0; y < face_size; ++y) {
    const std::size_t parent_row = static_cast<std::size_t>(y / 2) * parent_size;
    for (int x = 0; x < face_size; ++x) {
      const std::array<double, kSh9Coefficients> basis = ShBasis(TexelDirection(face, x, y, face_size));
      const double solid_angle = solid_angles[static_cast<std::size_t>(y) * face_size + x];
      for (int i = 0; i < kSh9Coefficients; ++i) {
        if (parent_size > 0) parent[i][parent_row + x / 2] += basis[i] * solid_angle;
      }
    }
  }
  for (int k = 1; k < count; ++k) {
    BasisLevel& level = pyramid.levels[k];
    const int size = level.size;
    const std::size_t face_offset = static_cast<std::size_t>(f) * size * size;
    for (int i = 0; i < kSh9Coefficients; ++i) {
      for (std::size_t t = 0; t < parent[i].size(); ++t) {
        level.weights[i][face_offset + t] = static_cast<float>(parent[i][t]);
      }
    }
    if (k + 1 == count) break;
    const int half = size / 2;
    for (int i = 0; i < kSh9Coefficients; ++i) {
      std::vector<double> next(static_cast<std::size_t>(half) * half, 0.0);
      auto child = [&](int cx, int cy) { return parent[i][static_cast<std::size_t>(cy) * size + cx]; };
      for (int y = 0; y < half; ++y) {
        for (int x = 0; x < half; ++x) {
          next[static_cast<std::size_t>(y) * half + x] = (child(2 * x, 2 * y) + child(2 * x + 1, 2 * y)) +
                                                         (child(2 * x, 2 * y + 1) + child(2 * x + 1, 2 * y + 1));
        }
      }
      parent[i] = std::move(next);
    }
  }
}

// Solid angles of every texel of a face of `size` (the same on all six faces), row-major.
std::vector<double> FaceSolidAngles(int size) {
  std::vector<double> solid_angles;
  solid_angles.reserve(static_cast<std::size_t>(size) * size);
  std::vector<double> row;
  for (int y = 0; y < size; ++y) {
    RowSolidAngles(y, size, row);
    solid_angles.insert(solid_angles.end(), row.begin(), row.end());
  }
  return solid_angles;
}

}  // namespace

FinestWeights BuildFinestWeights(int face_size) {
  assert(face_size >= 0);
  return MakeFinestWeights(FaceSolidAngles(face_size), face_size);
}

Sh9Rgb ProjectFinest(const CubeMap& map, const FinestWeights& weights) {
  const int size = map.face_size;
  assert(weights.q.size() == static_cast<std::size_t>(size) * size);
  Sh9Rgb sh;
  if (size == 0) return sh;
  kernels::CubeTexels texels;
  for (int f = 0; f < kCubeFaceCount; ++f) texels[f] = PixelFloats(map.faces[f], 0);
  kernels::CubeMomentSums moments;
  kernels::CubeMoments(texels, {weights.q.data(), weights.qr.data(), weights.qr2.data()}, size, moments);
  for (int f = 0; f < kCubeFaceCount; ++f) AddFaceFromMoments(moments[f], LinearFormOf(kAllCubeFaces[f]), sh.coefficients);
  return sh;
}

Sh9Rgb ProjectDirect(const CubeMap& env) {
  const int size = env.face_size;
  Sh9Rgb sh;
  std::vector<double> solid_angles;
  for (int y = 0; y < size; ++y) {
    RowSolidAngles(y, size, solid_angles);
    for (CubeFace face : kAllCubeFaces) {
      const Image& image = env.face(face);
      assert(image.width == size && image.height == size);
      AccumulateDirectRow(face, y, size, &image.at(0, y), solid_angles, sh.coefficients);
    }
  }
  return sh;
}

int LevelCount(int face_size) {
  if (!IsPowerOfTwo(face_size)) return 0;
  int count = 1;
  while (face_size > 1) {
    face_size >>= 1;
    ++count;
  }
  return count;
}

std::optional<CubeMipChain> BuildEnvironmentMips(const CubeMap& env) { return BuildEnvironmentMips(CubeMap(env)); }

std::optional<CubeMipChain> BuildEnvironmentMips(CubeMap&& env) {
  const int count = LevelCount(env.face_size);
  if (count == 0) return std::nullopt;
  CubeMipChain chain;
  chain.levels.reserve(count);
  const int face_size = env.face_size;
  chain.levels.push_back(std::move(env));
  for (int k = 1; k < count; ++k) chain.levels.emplace_back(face_size >> k);
  FillCoarserLevels(chain);
  return chain;
}

bool RefillEnvironmentMips(const CubeMap& env, CubeMipChain& chain) {
  const int count = LevelCount(env.face_size);
  if (count == 0) return false;
  if (!HasPyramidShape(chain, env.face_size)) {
    chain.levels.clear();
    chain.levels.reserve(count);
    for (int k = 0; k < count; ++k) chain.levels.emplace_back(env.face_size >> k);
  }
  if (count == 1) {
    chain.levels[0].faces = env.faces;
    return true;
  }
  // One pass over the environment: each pair of rows is copied into level 0 and, while still in
  // cache, halved into level 1.
  const int size = env.face_size;
  const std::size_t row_bytes = static_cast<std::size_t>(size) * sizeof(glm::vec3);
  for (int f = 0; f < kCubeFaceCount; ++f) {
    const Image& source = env.faces[f];
    Image& finest = chain.levels[0].faces[f];
    for (int y = 0; y < size; y += 2) {
      std::memcpy(PixelFloats(finest, y), PixelFloats(source, y), 2 * row_bytes);
      kernels::HalveRowPair(PixelFloats(finest, y), PixelFloats(finest, y + 1),
                            PixelFloats(chain.levels[1].faces[f], y / 2), size / 2);
    }
    FillLevelsFromTwo(chain, f);
  }
  return true;
}

std::optional<BasisPyramid> BuildBasisPyramid(int face_size, int threads,
                                              const std::function<void(double)>& progress, ThreadPool* pool) {
  assert(threads >= 1);
  const int count = LevelCount(face_size);
  if (count == 0) return std::nullopt;
  BasisPyramid pyramid;
  pyramid.face_size = face_size;
  pyramid.levels.resize(count);
  for (int k = 0; k < count; ++k) {
    BasisLevel& level = pyramid.levels[k];
    level.size = face_size >> k;
    if (k == 0) continue;  // level 0 is evaluated from texel coordinates (ProjectFinest), not stored
    for (auto& w : level.weights) w.assign(LevelTexels(level.size), 0.0f);
  }
  const std::vector<double> solid_angles = FaceSolidAngles(face_size);
  pyramid.finest = MakeFinestWeights(solid_angles, face_size);
  // Faces write disjoint parts of every level, so they are built in parallel, one task per face;
  // the result does not depend on `threads`.
  std::mutex progress_mutex;
  int faces_done = 0;
  ThreadPool& workers = pool != nullptr ? *pool : ThreadPool::Default();
  workers.Run(kCubeFaceCount, threads, [&](std::size_t f, int) {
    BuildBasisFace(static_cast<int>(f), solid_angles, pyramid);
    if (progress) {
      std::lock_guard<std::mutex> lock(progress_mutex);
      progress(static_cast<double>(++faces_done) / kCubeFaceCount);
    }
  });
  return pyramid;
}

Sh9Rgb ProjectLevel(const CubeMipChain& env, const BasisPyramid& basis, int level) {
  assert(!env.levels.empty() && env.levels[0].face_size == basis.face_size);
  assert(level >= 0 && level < static_cast<int>(env.levels.size()) &&
         level < static_cast<int>(basis.levels.size()));
  const CubeMap& map = env.levels[level];
  if (level == 0) return ProjectFinest(map, basis.finest);
  const BasisLevel& weights = basis.levels[level];
  const int size = map.face_size;
  assert(weights.size == size);

  // One de-interleaved radiance row (converted to double once, used by all nine weights), reused
  // for every row of every face.
  std::vector<double> r(size), g(size), b(size);
  std::array<kernels::ChannelSums, kSh9Coefficients> sums{};
  for (int f = 0; f < kCubeFaceCount; ++f) {
    const Image& image = map.faces[f];
    for (int y = 0; y < size; ++y) {
      const glm::vec3* row = &image.at(0, y);
      for (int x = 0; x < size; ++x) {
        r[x] = row[x].x;
        g[x] = row[x].y;
        b[x] = row[x].z;
      }
      std::array<const float*, kSh9Coefficients> weight_rows;
      for (int i = 0; i < kSh9Coefficients; ++i) weight_rows[i] = weights.Row(i, f, y);
      kernels::AddWeightedRowSums(weight_rows.data(), kSh9Coefficients, {r.data(), g.data(), b.data()}, size,
                                  sums.data());
    }
  }
  Sh9Rgb sh;
  for (int i = 0; i < kSh9Coefficients; ++i) sh.coefficients[i] = glm::dvec3(sums[i][0], sums[i][1], sums[i][2]);
  return sh;
}

}  // namespace vs11::irradiance
