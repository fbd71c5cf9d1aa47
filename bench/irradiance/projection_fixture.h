// Per-process fixtures for the coefficient and frame benchmarks: a sky environment, its mip chain and
// the basis pyramid of its face size, built once on first use (BuildBasisPyramid(1024): 25 MB and
// tens of milliseconds), and the two baselines: the obvious scalar double projection, and a plain
// loop over the same precomputed texel weights the fast path reads.
#pragma once

#include <cassert>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <optional>

#include "irradiance/io/cube_map.h"
#include "irradiance/io/environments.h"
#include "irradiance/sh/sh9.h"
#include "irradiance/sh/sh_projection.h"

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

// Radiance x basis x solid angle summed in double, one full-resolution texel at a time, with each
// texel's direction and nine basis values computed on the spot; `solid_angle(x, y, size)` gives the
// texel's solid angle (the same on every face).
template <class SolidAngle>
vs11::Sh9Rgb ProjectTexelByTexel(const irradiance::CubeMap& env, SolidAngle solid_angle) {
  vs11::Sh9Rgb sh;
  const int size = env.face_size;
  for (irradiance::CubeFace face : irradiance::kAllCubeFaces) {
    const irradiance::Image& image = env.face(face);
    for (int y = 0; y < size; ++y) {
      for (int x = 0; x < size; ++x) {
        const glm::dvec3 direction = irradiance::TexelDirection(face, x, y, size);
        const std::array<double, vs11::kSh9Coefficients> basis = vs11::ShBasis(direction);
        const glm::dvec3 weighted = glm::dvec3(image.at(x, y)) * solid_angle(x, y, size);
        for (int i = 0; i < vs11::kSh9Coefficients; ++i) sh.coefficients[i] += weighted * basis[i];
      }
    }
  }
  return sh;
}

// The obvious baseline: every texel's exact solid angle (four atan2) is computed on the spot too.
inline vs11::Sh9Rgb ProjectScalarDouble(const irradiance::CubeMap& env) {
  return ProjectTexelByTexel(env, [](int x, int y, int size) { return irradiance::TexelSolidAngle(x, y, size); });
}

// The fair baseline: the precomputation the fast path reads (the exact solid angle of each texel of
// a face, BasisPyramid::finest.q, built once outside the timed loop, as it is for ProjectLevel), used
// by a plain scalar loop: direction and basis per texel on the spot (a normalisation and a
// polynomial, as level 0 evaluates them from texel coordinates). It leaves out what
// ProjectScalarDouble recomputes every call (four atan2 per texel for the solid angle) and what
// ProjectLevel adds (SIMD float moments per row). BM_BasisPyramidBuild times the one-off build.
inline vs11::Sh9Rgb ProjectPlainLoop(const irradiance::CubeMap& env, const irradiance::FinestWeights& finest) {
  assert(finest.q.size() == static_cast<std::size_t>(env.face_size) * env.face_size);
  return ProjectTexelByTexel(env, [&finest](int x, int y, int size) {
    return static_cast<double>(finest.q[static_cast<std::size_t>(y) * size + x]);
  });
}

}  // namespace vs11::bench
