// Direct and mip-pyramid SH9 projection of cube environment maps. See sh_projection.h.
#include "irradiance/sh/sh_projection.h"

#include <algorithm>
#include <cmath>
#include <cassert>
#include <cstddef>
#include <mutex>

#include "irradiance/io/cube_map.h"
#include "irradiance/sh/projection_kernels.h"

namespace vs11::irradiance {
namespace {

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

// The finest level's weights of texel (x, y) of a face (see FinestWeights), from its solid angle q.
void StoreFinestWeights(int x, int y, int size, double q, FinestWeights& weights) {
  const double s = FaceCoordinate(x, size), t = FaceCoordinate(y, size);
  const std::size_t i = static_cast<std::size_t>(y) * size + x;
  const double r2 = 1.0 / (1.0 + s * s + t * t);
  weights.q[i] = static_cast<float>(q);
  weights.qr[i] = static_cast<float>(q * std::sqrt(r2));
  weights.qr2[i] = static_cast<float>(q * r2);
}

// The solid angles of texels (x0 .. x0 + count - 1, y) of a face of `size`, bit for bit
// TexelSolidAngle, from two rows of corner areas: `upper` holds corners (x0 .., y) on entry and
// corners (x0 .., y + 1) on return, so that the next row reuses them (one atan2 per texel).
void NextRowSolidAngles(int x0, int y, int count, int size, std::vector<double>& upper, std::vector<double>& lower,
                        std::vector<double>& out) {
  lower.resize(count + 1);
  for (int i = 0; i <= count; ++i) lower[i] = TexelCornerArea(x0 + i, y + 1, size);
  out.resize(count);
  for (int x = 0; x < count; ++x) out[x] = lower[x + 1] - lower[x] - upper[x + 1] + upper[x];
  upper.swap(lower);
}

// The corner areas of row y of corners, from corner x0 on (count + 1 of them).
std::vector<double> CornerRow(int x0, int y, int count, int size) {
  std::vector<double> row(count + 1);
  for (int i = 0; i <= count; ++i) row[i] = TexelCornerArea(x0 + i, y, size);
  return row;
}

// Tiles of the pyramid's build: at least kMinTile finest texels on an edge (or the whole face), and
// at most kTilesPerEdge of them on a face's edge (at most 64 tasks).
constexpr int kMinTile = 32;
constexpr int kTilesPerEdge = 8;

// A block's nine weights (kernels::kBlockMomentSlots) in double, before they are rounded to float.
using BlockMomentValues = std::array<double, kernels::kBlockMoments>;

// The nine products a finest texel adds to the weights of each block that holds it.
BlockMomentValues FinestBlockMoments(double q, double s, double t) {
  const double r2 = 1.0 / (1.0 + s * s + t * t);
  const double r_powers[3] = {1.0, std::sqrt(r2), r2};
  const double s_powers[2] = {1.0, s};
  const double t_powers[3] = {1.0, t, t * t};
  BlockMomentValues values;
  for (int j = 0; j < kernels::kBlockMoments; ++j) {
    const kernels::BlockMomentSlot slot = kernels::kBlockMomentSlots[j];
    values[j] = q * r_powers[kernels::kMomentPowerOfR[slot.moment]] * s_powers[kernels::kMomentPowerOfS[slot.moment]] *
                t_powers[slot.power_of_t];
  }
  return values;
}

void AddTo(BlockMomentValues& sum, const BlockMomentValues& term) {
  for (int j = 0; j < kernels::kBlockMoments; ++j) sum[j] += term[j];
}

// Rounds `blocks` (n x n block values at `level`, whose block (0, 0) is block (x0, y0) of the level)
// into the pyramid, and returns the next level's blocks: each the double sum of its four children,
// (upper left + upper right) + (lower left + lower right).
std::vector<BlockMomentValues> StoreAndHalve(const std::vector<BlockMomentValues>& blocks, int n, int x0, int y0,
                                             BasisLevel& level) {
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      const std::size_t to = static_cast<std::size_t>(y0 + y) * level.size + (x0 + x);
      for (int j = 0; j < kernels::kBlockMoments; ++j) {
        level.weights[j][to] = static_cast<float>(blocks[static_cast<std::size_t>(y) * n + x][j]);
      }
    }
  }
  const int half = n / 2;
  std::vector<BlockMomentValues> parents(static_cast<std::size_t>(half) * half);
  for (int y = 0; y < half; ++y) {
    for (int x = 0; x < half; ++x) {
      auto child = [&](int cx, int cy) { return blocks[static_cast<std::size_t>(2 * y + cy) * n + 2 * x + cx]; };
      BlockMomentValues upper = child(0, 0), lower = child(0, 1);
      AddTo(upper, child(1, 0));
      AddTo(lower, child(1, 1));
      AddTo(upper, lower);
      parents[static_cast<std::size_t>(y) * half + x] = upper;
    }
  }
  return parents;
}

// The finest weights and the coarse levels of the square tile of `tile` x `tile` finest texels whose
// upper left texel is (x0, y0) (tile a power of two dividing the face size), up to level
// log2(tile) - 1. Returns the tile's own nine sums in double: its one block of level log2(tile), not
// yet stored (BuildAboveTiles stores it with its neighbours).
BlockMomentValues BuildTile(int x0, int y0, int tile, BasisPyramid& pyramid) {
  const int size = pyramid.face_size;
  const int half = std::max(tile / 2, 1);
  // Level 1 of the tile (or, for a one-texel face, its only texel), summed in double.
  std::vector<BlockMomentValues> blocks(static_cast<std::size_t>(half) * half, BlockMomentValues{});
  std::vector<double> upper = CornerRow(x0, y0, tile, size), lower, solid_angles;
  for (int y = 0; y < tile; ++y) {
    NextRowSolidAngles(x0, y0 + y, tile, size, upper, lower, solid_angles);
    const double t = FaceCoordinate(y0 + y, size);
    for (int x = 0; x < tile; ++x) {
      StoreFinestWeights(x0 + x, y0 + y, size, solid_angles[x], pyramid.finest);
      AddTo(blocks[static_cast<std::size_t>(y / 2) * half + x / 2],
            FinestBlockMoments(solid_angles[x], FaceCoordinate(x0 + x, size), t));
    }
  }
  for (int n = tile / 2, k = 1; n > 1; n /= 2, ++k) blocks = StoreAndHalve(blocks, n, x0 >> k, y0 >> k, pyramid.levels[k]);
  return blocks.front();
}

// Level `level` (n x n blocks, one per tile, from BuildTile) and every coarser level.
void BuildAboveTiles(std::vector<BlockMomentValues> blocks, int n, int level, BasisPyramid& pyramid) {
  if (level == 0) return;  // a face of one texel has no coarse levels
  for (; n >= 1; n /= 2, ++level) blocks = StoreAndHalve(blocks, n, 0, 0, pyramid.levels[level]);
}

// Solid angles of every texel of a face of `size` (the same on all six faces), row-major.
std::vector<double> FaceSolidAngles(int size) {
  std::vector<double> solid_angles;
  solid_angles.reserve(static_cast<std::size_t>(size) * size);
  if (size == 0) return solid_angles;
  std::vector<double> upper = CornerRow(0, 0, size, size), lower, row;
  for (int y = 0; y < size; ++y) {
    NextRowSolidAngles(0, y, size, size, upper, lower, row);
    solid_angles.insert(solid_angles.end(), row.begin(), row.end());
  }
  return solid_angles;
}

// Terms radiance x weight are formed and summed (16 to a lane) in float, so radiance above about
// FLT_MAX / 34 (weights reach 2.1 sr on a 1 x 1 face) overflows them. Such a projection is run
// again with every weight scaled by 2^-kOverflowShift, which keeps the terms below 2^126 for any
// finite radiance, and its sums scaled back in double: scaling by a power of two is exact, so the
// result is the one float arithmetic without an upper exponent limit would give (terms under
// 2^-120, negligible beside such radiance, lose bits as subnormals). Maps that do not overflow
// never take this path and keep their bits.
constexpr int kOverflowShift = 6;

bool AllFinite(const kernels::CubeMomentSums& moments) {
  for (const kernels::FaceMomentSums& face : moments) {
    for (const auto& power : face) {
      for (double sum : power) {
        if (!std::isfinite(sum)) return false;
      }
    }
  }
  return true;
}

std::vector<float> ScaledDown(const float* weights, std::size_t count) {
  std::vector<float> scaled(weights, weights + count);
  for (float& w : scaled) w = std::ldexp(w, -kOverflowShift);
  return scaled;
}

// `moments(weights)` computes a cube's moment sums from its weights (kernels::CubeMoments or
// CubeBlockMoments); `weights` are the level's, `count` floats each. Runs it once, and again with
// scaled-down weights when the float terms overflowed.
template <std::size_t kWeightArrays, class Moments>
kernels::CubeMomentSums OverflowSafeMoments(const std::array<const float*, kWeightArrays>& weights,
                                            std::size_t count, const Moments& moments) {
  kernels::CubeMomentSums sums;
  moments(weights, sums);
  if (AllFinite(sums)) return sums;
  std::array<std::vector<float>, kWeightArrays> scaled;
  std::array<const float*, kWeightArrays> scaled_weights;
  for (std::size_t j = 0; j < kWeightArrays; ++j) {
    scaled[j] = ScaledDown(weights[j], count);
    scaled_weights[j] = scaled[j].data();
  }
  moments(scaled_weights, sums);
  for (kernels::FaceMomentSums& face : sums) {
    for (auto& power : face) {
      for (double& sum : power) sum = std::ldexp(sum, kOverflowShift);
    }
  }
  return sums;
}

}  // namespace

FinestWeights BuildFinestWeights(int face_size) {
  assert(face_size >= 0);
  const std::vector<double> solid_angles = FaceSolidAngles(face_size);
  FinestWeights weights;
  weights.q.resize(solid_angles.size());
  weights.qr.resize(solid_angles.size());
  weights.qr2.resize(solid_angles.size());
  for (int y = 0; y < face_size; ++y) {
    for (int x = 0; x < face_size; ++x) {
      StoreFinestWeights(x, y, face_size, solid_angles[static_cast<std::size_t>(y) * face_size + x], weights);
    }
  }
  return weights;
}

Sh9Rgb ProjectFinest(const CubeMap& map, const FinestWeights& weights) {
  const int size = map.face_size;
  assert(weights.q.size() == static_cast<std::size_t>(size) * size);
  Sh9Rgb sh;
  if (size == 0) return sh;
  kernels::CubeTexels texels;
  for (int f = 0; f < kCubeFaceCount; ++f) texels[f] = PixelFloats(map.faces[f], 0);
  const std::array<const float*, 3> face_weights = {weights.q.data(), weights.qr.data(), weights.qr2.data()};
  const kernels::CubeMomentSums moments = OverflowSafeMoments(
      face_weights, weights.q.size(), [&](const std::array<const float*, 3>& w, kernels::CubeMomentSums& out) {
        kernels::CubeMoments(texels, {w[0], w[1], w[2]}, size, out);
      });
  for (int f = 0; f < kCubeFaceCount; ++f) AddFaceFromMoments(moments[f], LinearFormOf(kAllCubeFaces[f]), sh.coefficients);
  return sh;
}

Sh9Rgb ProjectDirect(const CubeMap& env) {
  const int size = env.face_size;
  Sh9Rgb sh;
  if (size == 0) return sh;
  std::vector<double> upper = CornerRow(0, 0, size, size), lower, solid_angles;
  for (int y = 0; y < size; ++y) {
    NextRowSolidAngles(0, y, size, size, upper, lower, solid_angles);
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
  // One pass over the environment: each pair of rows is copied into level 0 and halved into level 1
  // from the same loads.
  const int size = env.face_size;
  for (int f = 0; f < kCubeFaceCount; ++f) {
    const Image& source = env.faces[f];
    Image& finest = chain.levels[0].faces[f];
    for (int y = 0; y < size; y += 2) {
      kernels::CopyAndHalveRowPair(PixelFloats(source, y), PixelFloats(source, y + 1), PixelFloats(finest, y),
                                   PixelFloats(finest, y + 1), PixelFloats(chain.levels[1].faces[f], y / 2), size / 2);
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
    for (auto& w : level.weights) w.resize(static_cast<std::size_t>(level.size) * level.size);
  }
  const std::size_t face_texels = static_cast<std::size_t>(face_size) * face_size;
  pyramid.finest.q.resize(face_texels);
  pyramid.finest.qr.resize(face_texels);
  pyramid.finest.qr2.resize(face_texels);
  // Tiles write disjoint parts of every level, so they are built in parallel, and the levels above
  // them from their sums afterwards; the result does not depend on `threads`.
  const int tile = std::max(std::min(face_size, kMinTile), face_size / kTilesPerEdge);
  const int tiles_per_edge = face_size / tile;
  const std::size_t tile_count = static_cast<std::size_t>(tiles_per_edge) * tiles_per_edge;
  std::vector<BlockMomentValues> tile_sums(tile_count);
  std::mutex progress_mutex;
  std::size_t tiles_done = 0;
  ThreadPool& workers = pool != nullptr ? *pool : ThreadPool::Default();
  workers.Run(tile_count, threads, [&](std::size_t i, int) {
    const int x0 = static_cast<int>(i % tiles_per_edge) * tile, y0 = static_cast<int>(i / tiles_per_edge) * tile;
    tile_sums[i] = BuildTile(x0, y0, tile, pyramid);
    if (progress) {
      std::lock_guard<std::mutex> lock(progress_mutex);
      progress(static_cast<double>(++tiles_done) / static_cast<double>(tile_count));
    }
  });
  BuildAboveTiles(std::move(tile_sums), tiles_per_edge, count - LevelCount(tiles_per_edge), pyramid);
  return pyramid;
}

std::size_t ProjectionMemoryBytes(int face_size) {
  const std::size_t face_texels = static_cast<std::size_t>(std::max(face_size, 0)) * std::max(face_size, 0);
  constexpr std::size_t kCubeAndMipBytesPerFaceTexel = kCubeFaceCount * sizeof(glm::vec3) * 4 / 3;
  constexpr std::size_t kBasisBytesPerFaceTexel = 24;
  return face_texels * (kCubeAndMipBytesPerFaceTexel + kBasisBytesPerFaceTexel);
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
  kernels::CubeTexels texels;
  for (int f = 0; f < kCubeFaceCount; ++f) texels[f] = PixelFloats(map.faces[f], 0);
  kernels::BlockWeights block_weights;
  for (int j = 0; j < kernels::kBlockMoments; ++j) block_weights[j] = weights.weights[j].data();
  const kernels::CubeMomentSums moments = OverflowSafeMoments(
      block_weights, static_cast<std::size_t>(size) * size,
      [&](const kernels::BlockWeights& w, kernels::CubeMomentSums& out) {
        kernels::CubeBlockMoments(texels, w, size, out);
      });
  Sh9Rgb sh;
  for (int f = 0; f < kCubeFaceCount; ++f) AddFaceFromMoments(moments[f], LinearFormOf(kAllCubeFaces[f]), sh.coefficients);
  return sh;
}

BlockMomentCombination BlockMomentCombinationFactors() {
  BlockMomentCombination combination{};
  for (int f = 0; f < kCubeFaceCount; ++f) {
    for (int j = 0; j < kernels::kBlockMoments; ++j) {
      // The sums are linear in the moments: one unit moment sum (red channel) gives column j.
      kernels::FaceMomentSums unit{};
      const kernels::BlockMomentSlot slot = kernels::kBlockMomentSlots[j];
      unit[slot.power_of_t][3 * slot.moment] = 1.0;
      std::array<glm::dvec3, kSh9Coefficients> sums{};
      AddFaceFromMoments(unit, LinearFormOf(kAllCubeFaces[f]), sums);
      for (int lm = 0; lm < kSh9Coefficients; ++lm) combination[f][lm][j] = sums[lm].x;
    }
  }
  return combination;
}

}  // namespace vs11::irradiance
