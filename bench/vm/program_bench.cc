// Every program of programs/*.vsh on each engine: BM_Program/<name>/<engine>, 65 536 vertices (the
// sh9 references add their 14 fixed normals), items_per_second = vertices per second, and the
// program's instruction-slot count (vm/core/program.h ComputeStats) as the counter "slots".
//
// /jit runs the CPU's best jit instruction set; /jit_avx2 is added where AVX-512 is the best, and
// beside it /batch_avx2, the batch engine on Highway's AVX2 kernels (what an AVX2-only machine runs).
// BM_Program/skinning/<engine>/bones_shared_by_64 gives each run of 64 vertices one pair of bones.
// /batch_legacy and /jit_legacy run under --float-rules legacy (vm/core/float_rules.h).
// BM_Program/<name>/threads:T/<vertices> runs /jit with T threads (capped at the cores: the default
// pool's size) over 1024, 65536 and 1M vertices, real time (the CPU time of one thread would
// hide the others); the CPU column is the whole process's, so T threads against one show what the
// split costs in work, apart from the wall clock a loaded machine makes noisy.
//
// Inputs and constants come from the program's reference (vm/reference/program_references.h, named by
// its `; vs11: reference=` line). A program without a usable reference gets (x, y, z, 1) unit normals
// in every input register v0..v15 and random constants in [-1, 1].

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include <benchmark/benchmark.h>
#include <hwy/targets.h>

#include "bench/bench_common.h"
#include "vm/core/machine.h"
#include "vm/core/program.h"
#include "vm/engines/engine_factory.h"
#include "vm/engines/jit_compiler.h"
#include "vm/reference/program_references.h"
#include "vm/reference/verify.h"

namespace vs11::bench {
namespace {

constexpr int kProgramVertices = 65536;
constexpr int kInputRegisterCount = 16;  // v0..v15
constexpr int kThreadCounts[] = {1, 2, 4, 8, 16};
constexpr int kThreadVertexCounts[] = {1024, 65536, 1 << 20};

struct ProgramCase {
  ConstantBank constants;
  VertexArrays inputs;
};

ProgramCase FallbackCase(int vertices) {
  std::vector<int> registers(kInputRegisterCount);
  for (int i = 0; i < kInputRegisterCount; ++i) registers[i] = i;
  const SoaNormals normals = RandomUnitNormals(vertices);
  ProgramCase c{ConstantBank(), MakeInputArrays(static_cast<std::size_t>(vertices), registers)};
  for (int reg : registers) {
    std::copy(normals.x.begin(), normals.x.end(), c.inputs.lane(reg, 0));
    std::copy(normals.y.begin(), normals.y.end(), c.inputs.lane(reg, 1));
    std::copy(normals.z.begin(), normals.z.end(), c.inputs.lane(reg, 2));
    c.inputs.FillUniform(reg, 3, 1.0f);
  }
  std::mt19937_64 rng(kBenchSeed);
  std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
  for (int i = 0; i < c.constants.size(); ++i) {
    c.constants[i] = {uniform(rng), uniform(rng), uniform(rng), uniform(rng)};
  }
  return c;
}

ProgramCase CaseFor(const vs11::ProgramMetadata& metadata, int vertices) {
  const vs11::ReferenceInfo* info = vs11::FindReference(metadata.reference);
  if (info != nullptr) {
    vs11::ReferenceOptions options;
    options.coefficients = BenchCoefficients();
    options.samples = vertices;
    options.seed = kBenchSeed;
    vs11::Result<vs11::ReferenceCase> reference = info->build(metadata, options);
    if (reference) return {std::move(reference->constants), std::move(reference->inputs)};
  }
  return FallbackCase(vertices);
}

// Skinning's inputs with each run of 64 vertices given its first vertex's bones, as a mesh's
// neighbouring vertices share theirs (the reference draws two bones per vertex at random).
constexpr int kBoneIndexRegister = 2;  // programs/skinning.vsh: v2.x and v2.y select the bones
constexpr std::size_t kVerticesSharingBones = 64;
void ShareBones(VertexArrays& inputs) {
  for (int c = 0; c < 2; ++c) {
    float* index = inputs.lane(kBoneIndexRegister, c);
    for (std::size_t i = 0; i < inputs.count(); ++i) index[i] = index[i - i % kVerticesSharingBones];
  }
}

// `highway_target`: the Highway target the batch engine's kernels are taken from (0: the CPU's best).
void RunProgram(benchmark::State& state, const std::filesystem::path& path, std::string kind, EngineOptions options,
                int vertices, std::int64_t highway_target = 0, bool share_bones = false) {
  const vs11::ProgramForVerify loaded = LoadBenchProgram(path);
  const Program& program = *loaded.program;
  ProgramCase c = CaseFor(loaded.metadata, vertices);
  if (share_bones) ShareBones(c.inputs);
  const std::size_t count = c.inputs.count();
  VertexArrays outputs = MakeOutputArrays(count, program);
  if (highway_target != 0) hwy::SetSupportedTargetsForTest(highway_target);
  std::unique_ptr<Engine> engine = MakeEngine(kind, program, c.constants, options).value();
  if (highway_target != 0) hwy::SetSupportedTargetsForTest(0);
  for (auto _ : state) {
    if (const Status ran = engine->Run(c.inputs, outputs); !ran) {
      state.SkipWithError(ran.message().c_str());
      break;
    }
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(count));
  state.counters["slots"] = ComputeStats(program).slots;
}

// Registers one benchmark per (program, engine) before main runs.
const bool kRegistered = [] {
  std::vector<std::filesystem::path> paths;
  for (const auto& entry : std::filesystem::directory_iterator(ProgramsFolder())) {
    if (entry.path().extension() == ".vsh") paths.push_back(entry.path());
  }
  std::sort(paths.begin(), paths.end());
  for (const auto& path : paths) {
    const auto add = [&path](const std::string& label, std::string kind, EngineOptions options) {
      const std::string name = "BM_Program/" + path.stem().string() + "/" + label;
      benchmark::RegisterBenchmark(name.c_str(), [path, kind, options](benchmark::State& state) {
        RunProgram(state, path, kind, options, kProgramVertices);
      })->Unit(benchmark::kMicrosecond);
    };
    // /threads:T/<vertices>: the jit engine splitting calls over T threads of the default pool.
    // The split must pay wherever it happens: T threads never slower than one, at any size.
    for (const int threads : kThreadCounts) {
      if (threads > 2 && static_cast<unsigned>(threads) > std::thread::hardware_concurrency()) continue;
      const std::string name = "BM_Program/" + path.stem().string() + "/threads:" + std::to_string(threads);
      auto* bench = benchmark::RegisterBenchmark(name.c_str(), [path, threads](benchmark::State& state) {
        RunProgram(state, path, "jit", {.threads = threads}, static_cast<int>(state.range(0)));
      });
      for (const int vertices : kThreadVertexCounts) bench->Arg(vertices);
      bench->Unit(benchmark::kMicrosecond)->UseRealTime()->MeasureProcessCPUTime();
    }
    for (std::string kind : {"ref", "batch", "jit"}) {
      add(std::string(kind), kind, {});
    }
    // --float-rules legacy: what the compares and selects around every product cost.
    for (std::string kind : {"batch", "jit"}) {
      add(std::string(kind) + "_legacy", kind, {.float_rules = FloatRules::kLegacy});
    }
    // /jit is the CPU's best instruction set; the narrower ones it also runs are measured too.
    const std::vector<JitIsa> isas = jit::SupportedIsas();
    for (std::size_t k = 0; k + 1 < isas.size(); ++k) {
      add(std::string("jit_").append(kJitIsaNames.Name(isas[k])), "jit", WithJitIsa({}, isas[k]));
    }
    // The batch engine's AVX2 kernels beside jit_avx2: what an AVX2-only machine runs with either.
    if (isas.size() > 1 && (hwy::SupportedTargets() & HWY_AVX2) != 0) {
      const std::string name = "BM_Program/" + path.stem().string() + "/batch_avx2";
      benchmark::RegisterBenchmark(name.c_str(), [path](benchmark::State& state) {
        RunProgram(state, path, "batch", {}, kProgramVertices, HWY_AVX2);
      })->Unit(benchmark::kMicrosecond);
    }
    // /<engine>/bones_shared_by_64: skinning as a mesh gives it bones (ShareBones).
    if (path.stem() == "skinning") {
      std::vector<std::pair<std::string, EngineOptions>> engines = {{"batch", {}}, {"jit", {}}};
      if (isas.size() > 1) engines.emplace_back("jit_avx2", WithJitIsa({}, JitIsa::kAvx2));
      for (const auto& [label, options] : engines) {
        const std::string kind = label == "batch" ? "batch" : "jit";
        const std::string name = "BM_Program/skinning/" + label + "/bones_shared_by_64";
        benchmark::RegisterBenchmark(name.c_str(), [path, kind, options](benchmark::State& state) {
          RunProgram(state, path, kind, options, kProgramVertices, 0, /*share_bones=*/true);
        })->Unit(benchmark::kMicrosecond);
      }
    }
  }
  return true;
}();

}  // namespace
}  // namespace vs11::bench
