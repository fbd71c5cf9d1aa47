// Irradiance evaluation throughput (vertices per second, one thread): the paper's 11-instruction
// program (programs/sh9_irradiance.vsh, Table 1 constants at c0..c6, normal in v0, result in oD0) on
// the reference and batch engines, against the same polynomial in plain C++, scalar and vectorised.
//
//   BM_Irradiance_Reference/N     reference engine
//   BM_Irradiance_Batch/N         batch engine, threads = 1
//   BM_Irradiance_Jit/N           jit engine (the program compiled for the CPU's best instruction set),
//                                 threads = 1
//   BM_Irradiance_Jit_<isa>/N     the same, forced to avx2 or avx512 (each the CPU supports)
//   BM_Irradiance_JitThreads/N/threads:T  jit engine on T threads (wall-clock time)
//   BM_Irradiance_NativeScalar/N  EvalTable1Scalar (no vectorisation)
//   BM_Irradiance_NativeSimd/N    EvalTable1Simd (AVX-512 / AVX2 / SSE2 by multi-versioning)

#include <array>
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "bench/bench_common.h"
#include "irradiance/sh/sh9.h"
#include "vm/core/machine.h"
#include "vm/engines/engine_factory.h"
#include "vm/engines/jit_compiler.h"

namespace vs11::bench {
namespace {

// The Table 1 registers as plain floats, hoisted out of the loops so the compiler sees scalars.
struct Table1Floats {
  std::array<float, 4> a[3];
  std::array<float, 4> b[3];
  float c[3];
};

Table1Floats Flatten(const vs11::SevenConstants& constants) {
  Table1Floats k{};
  for (int ch = 0; ch < 3; ++ch) {
    const glm::vec4& a = constants.registers[vs11::SevenConstants::kA + ch];
    const glm::vec4& b = constants.registers[vs11::SevenConstants::kB + ch];
    k.a[ch] = {a.x, a.y, a.z, a.w};
    k.b[ch] = {b.x, b.y, b.z, b.w};
    k.c[ch] = constants.registers[vs11::SevenConstants::kC][ch];
  }
  return k;
}

// One channel of the polynomial, in the VM's operation order: dp4 left to right, then
// x1 + (cC (x^2 - y^2) + x2).
inline float Channel(const std::array<float, 4>& a, const std::array<float, 4>& b, float c, float x, float y,
                     float z) {
  const float x1 = x * a[0] + y * a[1] + z * a[2] + a[3];
  const float x2 = x * y * b[0] + y * z * b[1] + z * z * b[2] + z * x * b[3];
  return x1 + (c * (x * x - y * y) + x2);
}

}  // namespace

__attribute__((noinline, optimize("no-tree-vectorize"))) void EvalTable1Scalar(
    const vs11::SevenConstants& constants, const float* x, const float* y, const float* z, float* r,
    float* g, float* b, std::size_t count) {
  const Table1Floats k = Flatten(constants);
  for (std::size_t i = 0; i < count; ++i) {
    r[i] = Channel(k.a[0], k.b[0], k.c[0], x[i], y[i], z[i]);
    g[i] = Channel(k.a[1], k.b[1], k.c[1], x[i], y[i], z[i]);
    b[i] = Channel(k.a[2], k.b[2], k.c[2], x[i], y[i], z[i]);
  }
}

namespace {

// The vectorised loop: every constant a local scalar, every array __restrict.
__attribute__((noinline, target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default"))) void EvalTable1Loop(
    const Table1Floats& constants, const float* __restrict x, const float* __restrict y,
    const float* __restrict z, float* __restrict r, float* __restrict g, float* __restrict b,
    std::size_t count) {
  const float ar0 = constants.a[0][0], ar1 = constants.a[0][1], ar2 = constants.a[0][2], ar3 = constants.a[0][3];
  const float ag0 = constants.a[1][0], ag1 = constants.a[1][1], ag2 = constants.a[1][2], ag3 = constants.a[1][3];
  const float ab0 = constants.a[2][0], ab1 = constants.a[2][1], ab2 = constants.a[2][2], ab3 = constants.a[2][3];
  const float br0 = constants.b[0][0], br1 = constants.b[0][1], br2 = constants.b[0][2], br3 = constants.b[0][3];
  const float bg0 = constants.b[1][0], bg1 = constants.b[1][1], bg2 = constants.b[1][2], bg3 = constants.b[1][3];
  const float bb0 = constants.b[2][0], bb1 = constants.b[2][1], bb2 = constants.b[2][2], bb3 = constants.b[2][3];
  const float cr = constants.c[0], cg = constants.c[1], cb = constants.c[2];
  for (std::size_t i = 0; i < count; ++i) {
    const float xi = x[i], yi = y[i], zi = z[i];
    const float xy = xi * yi, yz = yi * zi, zz = zi * zi, zx = zi * xi;
    const float d = xi * xi - yi * yi;
    r[i] = (xi * ar0 + yi * ar1 + zi * ar2 + ar3) + (cr * d + (xy * br0 + yz * br1 + zz * br2 + zx * br3));
    g[i] = (xi * ag0 + yi * ag1 + zi * ag2 + ag3) + (cg * d + (xy * bg0 + yz * bg1 + zz * bg2 + zx * bg3));
    b[i] = (xi * ab0 + yi * ab1 + zi * ab2 + ab3) + (cb * d + (xy * bb0 + yz * bb1 + zz * bb2 + zx * bb3));
  }
}

}  // namespace

void EvalTable1Simd(const vs11::SevenConstants& constants, const float* x, const float* y, const float* z,
                    float* r, float* g, float* b, std::size_t count) {
  const Table1Floats k = Flatten(constants);
  EvalTable1Loop(k, x, y, z, r, g, b, count);
}

namespace {

void RunEngine(benchmark::State& state, std::string kind, EngineOptions options = {}) {
  const std::size_t count = static_cast<std::size_t>(state.range(0));
  const vs11::ProgramForVerify loaded = LoadBenchProgram(ProgramPath("sh9_irradiance.vsh"));
  const Program& program = *loaded.program;
  const ConstantBank bank = Table1Bank(vs11::PackTable1(BenchCoefficients()));
  VertexArrays inputs = NormalInputs(RandomUnitNormals(count));
  inputs.FillUniform(0, 3, 1.0f);  // w is no data: a lane of 1s, as irrmap leaves it (NormalInputs writes it)
  VertexArrays outputs = MakeOutputArrays(count, program);
  std::unique_ptr<Engine> engine = MakeEngine(kind, program, bank, options).value();
  for (auto _ : state) {
    if (const Status ran = engine->Run(inputs, outputs); !ran) {
      state.SkipWithError(ran.message().c_str());
      break;
    }
    benchmark::DoNotOptimize(outputs.lane(static_cast<int>(OutputSlot::kDiffuse), 0));
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(count));
}

void BM_Irradiance_Reference(benchmark::State& state) { RunEngine(state, "ref"); }
void BM_Irradiance_Batch(benchmark::State& state) { RunEngine(state, "batch"); }
void BM_Irradiance_Jit(benchmark::State& state) { RunEngine(state, "jit"); }
void BM_Irradiance_JitThreads(benchmark::State& state) {
  RunEngine(state, "jit", {.threads = static_cast<int>(state.range(1))});
}

template <auto kEval>
void RunNative(benchmark::State& state) {
  const std::size_t count = static_cast<std::size_t>(state.range(0));
  const vs11::SevenConstants constants = vs11::PackTable1(BenchCoefficients());
  const SoaNormals normals = RandomUnitNormals(count);
  std::vector<float> r(count), g(count), b(count);
  for (auto _ : state) {
    kEval(constants, normals.x.data(), normals.y.data(), normals.z.data(), r.data(), g.data(), b.data(), count);
    benchmark::DoNotOptimize(r.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(count));
}

void BM_Irradiance_NativeScalar(benchmark::State& state) { RunNative<EvalTable1Scalar>(state); }
void BM_Irradiance_NativeSimd(benchmark::State& state) { RunNative<EvalTable1Simd>(state); }

#define VS11_IRRADIANCE_SIZES Arg(1024)->Arg(65536)->Arg(1 << 20)
BENCHMARK(BM_Irradiance_Reference)->VS11_IRRADIANCE_SIZES;
BENCHMARK(BM_Irradiance_Batch)->VS11_IRRADIANCE_SIZES;
BENCHMARK(BM_Irradiance_Jit)->VS11_IRRADIANCE_SIZES;
// The threads' time is the wall clock's: CPU time would count the calling thread only.
BENCHMARK(BM_Irradiance_JitThreads)->ArgNames({"", "threads"})->Args({1 << 20, 1})->Args({1 << 20, 2})->UseRealTime();
BENCHMARK(BM_Irradiance_NativeScalar)->VS11_IRRADIANCE_SIZES;
BENCHMARK(BM_Irradiance_NativeSimd)->VS11_IRRADIANCE_SIZES;
#undef VS11_IRRADIANCE_SIZES

// Each instruction set the CPU runs, forced, so that one run on an AVX-512 machine measures both.
const bool kIsasRegistered = [] {
  for (JitIsa isa : jit::SupportedIsas()) {
    const std::string name = std::string("BM_Irradiance_Jit_").append(kJitIsaNames.Name(isa));
    benchmark::RegisterBenchmark(name.c_str(), [isa](benchmark::State& state) {
      RunEngine(state, "jit", WithJitIsa({}, isa));
    })->Arg(1024)->Arg(65536)->Arg(1 << 20);
  }
  return true;
}();

}  // namespace
}  // namespace vs11::bench
