// Cost of one coefficient update (wall time, UseRealTime) from a sky environment:
//
//   BM_Coefficients/<face>/<level>       ProjectLevel from a pre-built mip chain and basis pyramid
//   BM_EnvMips/<face>                    BuildEnvironmentMips (a freshly allocated pyramid per call)
//   BM_EnvMipsRefill/<face>              RefillEnvironmentMips into one pyramid (the per-frame part
//                                        of the mip method in a real-time loop)
//   BM_Coefficients_ScalarDouble/<face>  ProjectScalarDouble: the obvious baseline, which computes
//                                        each texel's direction, basis and solid angle every call
//   BM_Coefficients_PlainLoop/<face>     ProjectPlainLoop: the fair baseline, a plain scalar double
//                                        loop over the same precomputed solid angles level 0 reads
//   BM_BasisPyramidBuild/<face>/<threads> BuildBasisPyramid: the one-off set-up ProjectLevel and the
//                                        plain loop read (built once per face size, not per frame)
//   BM_SkyGeneration/<face>              MakeSky (how long regenerating the environment itself takes)

#include <algorithm>
#include <cmath>

#include <benchmark/benchmark.h>

#include "bench/irradiance/projection_fixture.h"
#include "irradiance/io/environments.h"
#include "irradiance/sh/sh_projection.h"

namespace vs11::bench {
namespace {

constexpr int kFaceSizes[] = {256, 1024};

void BM_Coefficients(benchmark::State& state) {
  const ProjectionFixture& fixture = SkyFixture(static_cast<int>(state.range(0)));
  const int level = static_cast<int>(state.range(1));
  for (auto _ : state) {
    benchmark::DoNotOptimize(irradiance::ProjectLevel(fixture.mips, fixture.basis, level));
  }
  const int size = fixture.env.face_size >> level;
  state.counters["texels"] = 6.0 * size * size;
}
BENCHMARK(BM_Coefficients)
    ->Apply([](benchmark::internal::Benchmark* b) {
      for (int face : kFaceSizes) {
        for (int level = 0; level < irradiance::LevelCount(face); ++level) b->Args({face, level});
      }
    })
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

void BM_EnvMips(benchmark::State& state) {
  const ProjectionFixture& fixture = SkyFixture(static_cast<int>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(irradiance::BuildEnvironmentMips(fixture.env));
}
BENCHMARK(BM_EnvMips)->Arg(256)->Arg(1024)->UseRealTime()->Unit(benchmark::kMillisecond);

void BM_EnvMipsRefill(benchmark::State& state) {
  const ProjectionFixture& fixture = SkyFixture(static_cast<int>(state.range(0)));
  irradiance::CubeMipChain mips = fixture.mips;
  for (auto _ : state) {
    irradiance::RefillEnvironmentMips(fixture.env, mips);
    benchmark::ClobberMemory();
  }
}
BENCHMARK(BM_EnvMipsRefill)->Arg(256)->Arg(1024)->UseRealTime()->Unit(benchmark::kMillisecond);

void BM_Coefficients_ScalarDouble(benchmark::State& state) {
  const ProjectionFixture& fixture = SkyFixture(static_cast<int>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(ProjectScalarDouble(fixture.env));
}
BENCHMARK(BM_Coefficients_ScalarDouble)->Arg(256)->Arg(1024)->UseRealTime()->Unit(benchmark::kMillisecond);

// Largest difference between two projections, relative to the largest coefficient of `reference`.
double RelativeDifference(const vs11::Sh9Rgb& value, const vs11::Sh9Rgb& reference) {
  double largest = 0, difference = 0;
  for (int i = 0; i < vs11::kSh9Coefficients; ++i) {
    for (int c = 0; c < 3; ++c) {
      largest = std::max(largest, std::abs(reference.coefficients[i][c]));
      difference = std::max(difference, std::abs(value.coefficients[i][c] - reference.coefficients[i][c]));
    }
  }
  return difference / largest;
}

void BM_Coefficients_PlainLoop(benchmark::State& state) {
  const ProjectionFixture& fixture = SkyFixture(static_cast<int>(state.range(0)));
  const irradiance::FinestWeights& finest = fixture.basis.finest;
  for (auto _ : state) benchmark::DoNotOptimize(ProjectPlainLoop(fixture.env, finest));
  // The same projection as the obvious baseline, up to the float rounding of the stored weights.
  state.counters["rel_diff_vs_scalar_double"] =
      RelativeDifference(ProjectPlainLoop(fixture.env, finest), ProjectScalarDouble(fixture.env));
}
BENCHMARK(BM_Coefficients_PlainLoop)->Arg(256)->Arg(1024)->UseRealTime()->Unit(benchmark::kMillisecond);

void BM_BasisPyramidBuild(benchmark::State& state) {
  const int face = static_cast<int>(state.range(0)), threads = static_cast<int>(state.range(1));
  for (auto _ : state) benchmark::DoNotOptimize(irradiance::BuildBasisPyramid(face, threads));
}
BENCHMARK(BM_BasisPyramidBuild)
    ->Args({256, 1})
    ->Args({256, 2})
    ->Args({1024, 2})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

void BM_SkyGeneration(benchmark::State& state) {
  const int face = static_cast<int>(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(irradiance::MakeSky(face));
}
BENCHMARK(BM_SkyGeneration)->Arg(256)->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace vs11::bench
