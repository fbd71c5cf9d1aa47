// Per-process fixtures for the coefficient and frame benchmarks: a sky environment, its mip chain and
// the basis pyramid of its face size, built once on first use (BuildBasisPyramid(1024) alone takes
// about 300 MB and seconds), and the two baselines: the obvious scalar double projection, and a plain
// loop over the same precomputed texel weights the fast path reads.
#pragma once

#include <cassert>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <optional>

#include "irradiance/cube_map.h"
#include "irradiance/environments.h"
#include "irradiance/sh9.h"
#include "irradiance/sh_projection.h"

namespace vs11::bench {

struct ProjectionFixture {
  irradiance::CubeMap env;
  irradiance::CubeMipChain mips;
  irradiance::BasisPyramid basis;
};

// The default sky (environments.h) at `face_size` (a power of two), with its pyramids; built on first
// use and kept for the rest of the process. Not thread-safe (benchmarks register and run on one thread).
inline const ProjectionFixture& SkyFixture(int face_size) {
  static std::map<int, std::unique_ptr<ProjectionFixture>> fixtures;
  std::unique_ptr<ProjectionFixture>& slot = fixtures[face_size];
  if (!slot) {
    auto fixture = std::make_unique<ProjectionFixture>();
    fixture->env = irradiance::MakeSky(face_size);
    std::optional<irradiance::CubeMipChain> mips = irradiance::BuildEnvironmentMips(fixture->env);
    std::optional<irradiance::BasisPyramid> basis = irradiance::BuildBasisPyramid(face_size);
    if (!mips || !basis) {
      std::fprintf(stderr, "vs11_bench: face size %d is not a power of two\n", face_size);
      std::abort();
    }
    fixture->mips = std::move(*mips);
    fixture->basis = std::move(*basis);
    slot = std::move(fixture);
  }
  return *slot;
}

// The baseline projection: for every full-resolution texel, its direction, the nine basis functions
// and its exact solid angle are computed on the spot, and radiance x basis x solid angle is summed
// in double, one texel at a time.
inline irradiance::Sh9Rgb ProjectScalarDouble(const irradiance::CubeMap& env) {
  irradiance::Sh9Rgb sh;
  const int size = env.face_size;
  for (irradiance::CubeFace face : irradiance::kAllCubeFaces) {
    const irradiance::Image& image = env.face(face);
    for (int y = 0; y < size; ++y) {
      for (int x = 0; x < size; ++x) {
        const glm::dvec3 direction = irradiance::TexelDirection(face, x, y, size);
        const std::array<double, irradiance::kSh9Coefficients> basis = irradiance::ShBasis(direction);
        const glm::dvec3 weighted = glm::dvec3(image.at(x, y)) * irradiance::TexelSolidAngle(x, y, size);
        for (int i = 0; i < irradiance::kSh9Coefficients; ++i) sh.coefficients[i] += weighted * basis[i];
      }
    }
  }
  return sh;
}

// The fair baseline: the same precomputation as the fast path (the basis pyramid's level 0: each
// texel's nine basis values times its exact solid angle, as floats), read by a plain scalar loop
// that sums radiance x weight in double, texel by texel. It leaves out what ProjectScalarDouble
// recomputes every call (direction, basis, four atan2 per texel) and what ProjectLevel adds (SIMD
// over structure-of-arrays rows, fixed partial sums). The weights are built once, outside the
// timed loop, as they are for ProjectLevel; BM_BasisPyramidBuild times that build.
inline irradiance::Sh9Rgb ProjectPlainLoop(const irradiance::CubeMap& env, const irradiance::BasisLevel& level0) {
  assert(env.face_size == level0.size);
  irradiance::Sh9Rgb sh;
  const int size = env.face_size;
  std::size_t texel = 0;  // (face * size + y) * size + x, as BasisLevel stores it
  for (irradiance::CubeFace face : irradiance::kAllCubeFaces) {
    const irradiance::Image& image = env.face(face);
    for (int y = 0; y < size; ++y) {
      for (int x = 0; x < size; ++x, ++texel) {
        const glm::dvec3 radiance(image.at(x, y));
        for (int i = 0; i < irradiance::kSh9Coefficients; ++i) {
          sh.coefficients[i] += radiance * static_cast<double>(level0.weights[i][texel]);
        }
      }
    }
  }
  return sh;
}

}  // namespace vs11::bench
