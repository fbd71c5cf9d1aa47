// The memory limits the projection and the mip refill are measured against (wall time, one thread,
// the default sky's level 0 as the data):
//
//   BM_ReadCube/<face>       every float of the six faces read once and summed (SIMD, Highway's best
//                            target for this CPU): a full-resolution projection cannot be faster
//   BM_ReadWriteCube/<face>  every float read once and written once to a second cube of the same
//                            size: what any refill of a pyramid's level 0 must at least cost
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "bench/irradiance/cube_memory_bench.cc"
#include "hwy/foreach_target.h"  // IWYU pragma: keep

#include <cstddef>

#include "hwy/highway.h"

HWY_BEFORE_NAMESPACE();
namespace vs11::bench {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Four independent vector sums, so the loop runs at load speed rather than add latency.
float SumFloats(const float* HWY_RESTRICT data, std::size_t count) {
  const hn::ScalableTag<float> d;
  const std::size_t lanes = hn::Lanes(d);
  auto s0 = hn::Zero(d), s1 = hn::Zero(d), s2 = hn::Zero(d), s3 = hn::Zero(d);
  std::size_t i = 0;
  for (; i + 4 * lanes <= count; i += 4 * lanes) {
    s0 = hn::Add(s0, hn::LoadU(d, data + i));
    s1 = hn::Add(s1, hn::LoadU(d, data + i + lanes));
    s2 = hn::Add(s2, hn::LoadU(d, data + i + 2 * lanes));
    s3 = hn::Add(s3, hn::LoadU(d, data + i + 3 * lanes));
  }
  float sum = hn::GetLane(hn::SumOfLanes(d, hn::Add(hn::Add(s0, s1), hn::Add(s2, s3))));
  for (; i < count; ++i) sum += data[i];
  return sum;
}

void CopyFloats(const float* HWY_RESTRICT from, float* HWY_RESTRICT to, std::size_t count) {
  const hn::ScalableTag<float> d;
  const std::size_t lanes = hn::Lanes(d);
  std::size_t i = 0;
  for (; i + lanes <= count; i += lanes) hn::StoreU(hn::LoadU(d, from + i), d, to + i);
  for (; i < count; ++i) to[i] = from[i];
}

}  // namespace HWY_NAMESPACE
}  // namespace vs11::bench
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include <benchmark/benchmark.h>

#include "bench/irradiance/projection_fixture.h"
#include "irradiance/io/cube_map.h"

namespace vs11::bench {
namespace {

HWY_EXPORT(SumFloats);
HWY_EXPORT(CopyFloats);

std::size_t FaceFloats(const irradiance::Image& face) { return face.pixels.size() * 3; }

void BM_ReadCube(benchmark::State& state) {
  const irradiance::CubeMap& env = SkyFixture(static_cast<int>(state.range(0))).env;
  for (auto _ : state) {
    float sum = 0.0f;
    for (const irradiance::Image& face : env.faces) {
      sum += HWY_DYNAMIC_DISPATCH(SumFloats)(&face.pixels[0].x, FaceFloats(face));
    }
    benchmark::DoNotOptimize(sum);
  }
  state.counters["bytes"] = 6.0 * static_cast<double>(FaceFloats(env.faces[0]) * sizeof(float));
}
BENCHMARK(BM_ReadCube)->Arg(256)->Arg(1024)->UseRealTime()->Unit(benchmark::kMillisecond);

void BM_ReadWriteCube(benchmark::State& state) {
  const irradiance::CubeMap& env = SkyFixture(static_cast<int>(state.range(0))).env;
  irradiance::CubeMap copy(env.face_size);
  for (auto _ : state) {
    for (int f = 0; f < irradiance::kCubeFaceCount; ++f) {
      HWY_DYNAMIC_DISPATCH(CopyFloats)(&env.faces[f].pixels[0].x, &copy.faces[f].pixels[0].x, FaceFloats(env.faces[f]));
    }
    benchmark::ClobberMemory();
  }
}
BENCHMARK(BM_ReadWriteCube)->Arg(256)->Arg(1024)->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace vs11::bench
#endif  // HWY_ONCE
