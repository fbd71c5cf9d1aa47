// Projection of a cube environment map onto the nine SH coefficients, directly (the reference) and
// from mip levels (the paper's acceleration, section 3.2 step 2 and Fig. 2):
//
//   environment level k (mean radiance per texel)  x  basis level k (sum over the texel's 4^k
//   finest children of y_lm(dir) dOmega)  summed over the 6 (size >> k)^2 texels  ~=  L_lm
//
// (The basis levels are kept as nine block sums per texel of one face, from which each face's nine
// summed basis weights follow exactly: see BasisLevel.)
//
// Level 0 of the mip product is exactly the direct projection (up to float storage); coarser levels
// treat the radiance as constant over each 2^k x 2^k block, which blurs only what the nine
// coefficients cannot hold anyway once the block is small compared with the band-2 lobes.
#pragma once

#include <array>
#include <cstddef>
#include <functional>
#include <optional>
#include <vector>

#include "irradiance/io/cube_map.h"
#include "irradiance/sh/projection_kernels.h"
#include "vm/core/thread_pool.h"
#include "irradiance/sh/sh9.h"

namespace vs11::irradiance {

// L_lm = sum over every texel of radiance * y_lm(texel centre direction) * exact texel solid angle
// (TexelSolidAngle). Any face size >= 0 (0 gives all zeros). Precision: each face row is summed in
// double (the 27 running sums of one row), and the row sums are added into double totals, so a
// 2048-texel face adds 2048 terms per row and 6 x 2048 rows, far from losing float-sized precision;
// no Kahan compensation is used. Cost: O(6 size^2 x 9); the solid angles of a row are computed once
// and shared by the six faces.
Sh9Rgb ProjectDirect(const CubeMap& env);

// Number of mip levels from size x size down to 1 x 1, i.e. log2(size) + 1, for a face size that is a
// power of two; 0 when `face_size` is not a positive power of two.
int LevelCount(int face_size);

// An environment's mip pyramid: levels[0] is the map itself, levels[k] has faces of size >> k.
struct CubeMipChain {
  std::vector<CubeMap> levels;
};

// Builds the pyramid down to 1 x 1; each texel of level k + 1 is the mean (in float) of its 2 x 2
// children in level k, per face (faces are not filtered across their edges, which is exact for a
// box filter), finite for any finite texels (kernels::HalveRowPair). Returns std::nullopt when the face size is not a positive power of two: odd sizes
// have no exact 2 x 2 parentage, and dropping a row or column would silently lose light.
std::optional<CubeMipChain> BuildEnvironmentMips(const CubeMap& env);
// The same, taking `env` as level 0 instead of copying it (a map of 1024 faces is 75 MB). `env` is
// left moved-from, its face_size unchanged.
std::optional<CubeMipChain> BuildEnvironmentMips(CubeMap&& env);

// The same pyramid written into `chain` in place, for an environment that changes every frame: no
// allocation when `chain` already holds a pyramid of env's face size (one from BuildEnvironmentMips,
// or one filled here before), so its memory is not freed and page-faulted in again per frame; the
// result is bit-identical to BuildEnvironmentMips(env). Any other `chain` (empty, another size) is
// reshaped first, which allocates once. Returns false, leaving `chain` unchanged, when the face size
// is not a positive power of two.
bool RefillEnvironmentMips(const CubeMap& env, CubeMipChain& chain);

// One coarse level (k >= 1) of the basis pyramid, the same on all six faces: for each texel of a face
// (a block of 2^k x 2^k finest texels c), kernels::kBlockMoments sums over its children of
//   q_c, q_c r_c, q_c r_c s_c, q_c r_c t_c, q_c r_c^2, q_c r_c^2 s_c, q_c r_c^2 t_c, q_c r_c^2 s_c t_c, q_c r_c^2 t_c^2
// (kernels::kBlockMomentSlots), with q_c the child's exact solid angle (TexelSolidAngle), (s_c, t_c)
// its centre's face coordinates and r_c = 1 / sqrt(1 + s_c^2 + t_c^2). On every face, each of the nine
// summed basis weights sum_c y_lm(direction of c) q_c is a fixed linear combination of these (the
// face's direction is linear in 1, s and t), so they hold exactly the sums of the basis over the
// block, for six faces at once. Stored structure-of-arrays: weights[j][y * size + x], each formed in
// double and rounded to float once. Units: steradians.
struct BasisLevel {
  int size = 0;  // texels per face edge at this level
  std::array<std::vector<float>, kernels::kBlockMoments> weights;  // empty at level 0 (not stored)

  const float* Row(int moment, int y) const { return weights[moment].data() + static_cast<std::size_t>(y) * size; }
};

// What level-0 projection needs besides the texels, for each texel of one face (the same on all
// six), row-major, formed in double and rounded to float once: its exact solid angle q
// (TexelSolidAngle), q r and q r^2 with r = 1 / sqrt(1 + s^2 + t^2) (s, t: its centre's face
// coordinates). 12 bytes per texel of a face: 12 MB at 1024.
struct FinestWeights {
  std::vector<float> q, qr, qr2;
};

// FinestWeights for faces of `face_size` (>= 0).
FinestWeights BuildFinestWeights(int face_size);

// Level-0 projection without a pyramid: the same as ProjectLevel(chain, basis, 0), where `weights`
// are BuildFinestWeights(env.face_size) (asserted by size). The basis is evaluated from each
// texel's coordinates in SIMD float instead of read from memory: about 3x the time of merely
// reading the texels once, measured with AVX-512 (bench/README.md, "Issue #14"). Precision: every
// term radiance x (q, q r, q r s, q r^2 or q r^2 s) is formed in float and summed in float lanes
// over at most 16 terms per lane, then in double (never one float sum over the map, which the
// stability report shows failing at 2048^2); the result stays within 1e-6 of the largest
// coefficient of ProjectDirect, tested up to 2048 with a 1e6 sun. Results differ between SIMD
// targets (AVX-512, AVX2, ...) by float rounding only. Any finite radiance gives finite coefficients
// (double, possibly beyond float range): where the float terms overflow (texels above about
// FLT_MAX / 34), the projection is run again with its weights scaled by a power of two, exactly.
Sh9Rgb ProjectFinest(const CubeMap& env, const FinestWeights& weights);

// Built once per face size and reused for every environment of that size (paper section 3.3 step 1).
// Read-only once built: projections on several threads may share one (`irrmap batch` does).
struct BasisPyramid {
  int face_size = 0;              // size of level 0
  std::vector<BasisLevel> levels;  // LevelCount(face_size) levels, level k of size face_size >> k
  FinestWeights finest;             // what ProjectLevel reads at level 0
};

// Fills `finest` (BuildFinestWeights, bit for bit) and the coarse levels' block sums (BasisLevel),
// summed in double from the finest texels up (never from rounded floats), each stored value rounded
// to float once. Level 0's own basis weights are not stored (ProjectLevel evaluates level 0 from
// texel coordinates). Returns std::nullopt when `face_size` is not a positive power of two. The face
// is cut into up to 64 square tiles, built by up to `threads` (>= 1, asserted) threads, the calling
// one among them, with the same result for any count. Cost: one atan2 and one square root per texel
// of one face. Memory: 12 bytes per texel of a face for `finest`, and 9 floats per texel of a face's
// coarse levels, so about 12 more bytes per texel of a face: 25 MB at 1024, 100 MB at 2048.
// `progress`, when set, is called with the fraction done after each tile (from the worker threads,
// one call at a time). The threads are the caller and workers of `pool` (null: ThreadPool::Default()).
std::optional<BasisPyramid> BuildBasisPyramid(int face_size, int threads = 1,
                                              const std::function<void(double)>& progress = {},
                                              ThreadPool* pool = nullptr);

// About how many bytes projecting an environment of `face_size` holds at once: its cube map and mip
// pyramid (16 bytes per texel of the six faces) and the basis pyramid (24 bytes per texel of one
// face). Named in out-of-memory messages.
std::size_t ProjectionMemoryBytes(int face_size);

// Level 0 is ProjectFinest(env.levels[0], basis.finest). A coarser level k is projected the same way
// with the block sums of its BasisLevel as weights: for each face, the nine sums over its texels of
// mean radiance (float) x weight (float), each term formed in float and summed in float lanes over at
// most 16 terms per lane, then in double (kernels::CubeBlockMoments), and the face's coefficients
// from those sums in double. Precision: within 1e-6 of the largest coefficient of the texel-by-texel
// double projection of the same level (its radiance constant over each block, times y_lm q summed over
// every finest texel), tested at every level of faces 1 to 256 and 2048 with a 1e6 sun. Results
// differ between SIMD targets by float rounding only, and not with the thread count. Cost: 27 float
// multiply-adds per texel of the level, with 12 bytes of radiance and 6 bytes of weights (36 bytes
// shared by the six faces) read per texel. Finite radiance gives finite coefficients, as ProjectFinest.
// Preconditions (asserted): env.levels[0].face_size == basis.face_size and
// 0 <= level < env.levels.size() and level < basis.levels.size().
Sh9Rgb ProjectLevel(const CubeMipChain& env, const BasisPyramid& basis, int level);

// How ProjectLevel turns one face's sums of radiance x block moment (kernels::kBlockMomentSlots order,
// one channel) into that face's share of the nine coefficients: coefficient lm of channel c gains
// sum over slots j of combination[face][lm][j] x sum_texels(L_c x moment_j). The factors are the ones
// ProjectLevel applies itself (they hold the basis constants kShN* and the face's direction table),
// in double; a GPU or any other summation of the moments finishes with them.
using BlockMomentCombination =
    std::array<std::array<std::array<double, kernels::kBlockMoments>, kSh9Coefficients>, kCubeFaceCount>;
BlockMomentCombination BlockMomentCombinationFactors();

}  // namespace vs11::irradiance
