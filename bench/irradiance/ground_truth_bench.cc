// Cost of the brute-force ground truth (GroundTruthIrradiance, wall time, one thread so the figure
// is the kernel's, not the pool's):
//
//   BM_GroundTruth/<face>/<normals>   the clamped-cosine sum over every texel of the default sky for
//                                     each of <normals> SphereNormals

#include <benchmark/benchmark.h>

#include "irradiance/io/environments.h"
#include "irradiance/sh/ground_truth.h"

namespace vs11::bench {
namespace {

void BM_GroundTruth(benchmark::State& state) {
  const int face = static_cast<int>(state.range(0)), normal_count = static_cast<int>(state.range(1));
  const irradiance::CubeMap env = irradiance::MakeSky(face);
  const std::vector<glm::dvec3> normals = vs11::SphereNormals(normal_count);
  for (auto _ : state) benchmark::DoNotOptimize(irradiance::GroundTruthIrradiance(env, normals, 1));
  state.counters["texel_normals"] = benchmark::Counter(6.0 * face * face * normal_count,
                                                       benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_GroundTruth)->Args({16, 1000})->Args({64, 1000})->Args({128, 256})->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace vs11::bench
