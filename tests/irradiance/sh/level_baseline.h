// The texel-by-texel double baseline of every mip level, for the projection tests: what
// ProjectLevel(chain, basis, k) computes, written the slow and obvious way. Level k's radiance is
// constant over each 2^k x 2^k block of finest texels, so its projection is the sum over every finest
// texel c of L_k(block of c) y_lm(centre of c) TexelSolidAngle(c), all in double. Level 0 is
// ProjectDirect up to the order of the double additions.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

#include "irradiance/io/cube_map.h"
#include "irradiance/sh/sh9.h"
#include "irradiance/sh/sh_projection.h"

namespace vs11::irradiance::baseline {

// The largest coefficient magnitude of `sh` (over the nine coefficients and three channels).
inline double LargestCoefficient(const Sh9Rgb& sh) {
  double largest = 0.0;
  for (const glm::dvec3& c : sh.coefficients) largest = std::max({largest, std::abs(c.x), std::abs(c.y), std::abs(c.z)});
  return largest;
}

// The largest coefficient difference over the largest coefficient of `expected`.
inline double RelativeDifference(const Sh9Rgb& actual, const Sh9Rgb& expected) {
  double worst = 0.0;
  for (int i = 0; i < kSh9Coefficients; ++i) {
    for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(actual.coefficients[i][c] - expected.coefficients[i][c]));
  }
  return worst / LargestCoefficient(expected);
}

// The baseline of every level of `chain` (a pyramid from BuildEnvironmentMips). Memory: the face's
// corner areas and solid angles (16 bytes per texel of a face) and one face's level-1 weights in
// double (18 bytes per texel of a face): 140 MB at 2048. About 0.2 s per face at 2048.
inline std::vector<Sh9Rgb> LevelBaselines(const CubeMipChain& chain) {
  const int size = chain.levels[0].face_size;
  const int count = static_cast<int>(chain.levels.size());
  std::vector<Sh9Rgb> baselines(count);
  // TexelSolidAngle's sum over the texel's corners, from a table of corner areas (one atan2 per
  // texel instead of four; the same bits, as TexelCornerArea promises).
  std::vector<double> corners(static_cast<std::size_t>(size + 1) * (size + 1));
  for (int j = 0; j <= size; ++j) {
    for (int i = 0; i <= size; ++i) corners[static_cast<std::size_t>(j) * (size + 1) + i] = TexelCornerArea(i, j, size);
  }
  auto corner = [&](int i, int j) { return corners[static_cast<std::size_t>(j) * (size + 1) + i]; };
  std::vector<double> solid_angles(static_cast<std::size_t>(size) * size);
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      solid_angles[static_cast<std::size_t>(y) * size + x] =
          corner(x + 1, y + 1) - corner(x, y + 1) - corner(x + 1, y) + corner(x, y);
    }
  }
  for (int f = 0; f < kCubeFaceCount; ++f) {
    const CubeFace face = kAllCubeFaces[f];
    // weights[i][texel] at the current level: y_lm q summed over the texel's finest children.
    const int half = size / 2;
    std::array<std::vector<double>, kSh9Coefficients> weights;
    for (auto& w : weights) w.assign(static_cast<std::size_t>(half) * half, 0.0);
    for (int y = 0; y < size; ++y) {
      for (int x = 0; x < size; ++x) {
        const std::array<double, kSh9Coefficients> basis = ShBasis(TexelDirection(face, x, y, size));
        const double q = solid_angles[static_cast<std::size_t>(y) * size + x];
        const glm::dvec3 radiance(chain.levels[0].faces[f].at(x, y));
        for (int i = 0; i < kSh9Coefficients; ++i) {
          baselines[0].coefficients[i] += radiance * (basis[i] * q);
          if (half > 0) weights[i][static_cast<std::size_t>(y / 2) * half + x / 2] += basis[i] * q;
        }
      }
    }
    for (int k = 1; k < count; ++k) {
      const int n = size >> k;
      const Image& level = chain.levels[k].faces[f];
      for (int y = 0; y < n; ++y) {
        for (int x = 0; x < n; ++x) {
          const glm::dvec3 radiance(level.at(x, y));
          for (int i = 0; i < kSh9Coefficients; ++i) {
            baselines[k].coefficients[i] += radiance * weights[i][static_cast<std::size_t>(y) * n + x];
          }
        }
      }
      if (k + 1 == count) break;
      for (auto& w : weights) {
        std::vector<double> parent(static_cast<std::size_t>(n / 2) * (n / 2), 0.0);
        for (int y = 0; y < n; ++y) {
          for (int x = 0; x < n; ++x) parent[static_cast<std::size_t>(y / 2) * (n / 2) + x / 2] += w[static_cast<std::size_t>(y) * n + x];
        }
        w = std::move(parent);
      }
    }
  }
  return baselines;
}

}  // namespace vs11::irradiance::baseline
