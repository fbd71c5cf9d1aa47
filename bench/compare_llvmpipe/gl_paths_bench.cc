// The gl engine's two paths on Mesa's llvmpipe against the jit, per program of programs/*.vsh and a
// vs_2_0 skinning loop over bones (kSkinningLoopVs20):
// BM_GlPath/<program>/<compute|transform-feedback|jit>/<vertices>, each an Engine::Run as a caller
// makes it (the gl paths: inputs uploaded, the shader run, outputs read back into VertexArrays), real
// time (llvmpipe runs its own threads), items_per_second = vertices per second. Inputs: unit normals
// in every register v0..v15, constants in [-1, 1]. The results are in bench/README.md ("The gl
// engine's compute path").
#include <algorithm>
#include <filesystem>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <benchmark/benchmark.h>

#include "bench/bench_common.h"
#include "vm/asm/assembler.h"
#include "vm/reference/verify.h"
#include "vm/engines/engine_factory.h"
#include "vm/gl/gl_engine.h"

namespace vs11::bench {
namespace {

// A vs_2_0 skinning program with a loop over its bones (i0.x = 4 bones, 3x4 matrices from c10, aL
// stepping 3 rows): each vertex blends the bones' transforms of its position by its weights in v1, taken
// in turn by rotating them through r3 (vs_2_0 has no v[aL]). The gl engine runs its specialisation for
// i0, as the jit does.
constexpr const char* kSkinningLoopVs20 =
    "vs_2_0\n"
    "defi i0, 4, 10, 3, 0\n"
    "def c9, 0, 0, 0, 1\n"
    "dcl_position v0\n"
    "dcl_blendweight v1\n"
    "dcl_normal v2\n"
    "mov r0, c9\n"
    "mov r4, c9\n"
    "mov r3, v1\n"
    "loop aL, i0\n"
    "dp4 r1.x, v0, c0[aL]\n"
    "dp4 r1.y, v0, c1[aL]\n"
    "dp4 r1.z, v0, c2[aL]\n"
    "mad r0.xyz, r1, r3.x, r0\n"
    "dp3 r2.x, v2, c0[aL]\n"
    "dp3 r2.y, v2, c1[aL]\n"
    "dp3 r2.z, v2, c2[aL]\n"
    "mad r4.xyz, r2, r3.x, r4\n"
    "mov r3, r3.yzwx\n"
    "endloop\n"
    "m4x4 oPos, r0, c0\n"
    "mov oT0, r4\n";

struct Case {
  Program program;
  ConstantBank constants;
  VertexArrays inputs;
};

Case MakeCase(const Program& program, std::size_t vertices) {
  std::vector<int> registers(kInputRegisterCount);
  for (int i = 0; i < kInputRegisterCount; ++i) registers[static_cast<std::size_t>(i)] = i;
  const SoaNormals normals = RandomUnitNormals(vertices);
  Case c{program, ConstantBank(), MakeInputArrays(vertices, registers)};
  for (int reg : registers) {
    std::copy(normals.x.begin(), normals.x.end(), c.inputs.lane(reg, 0));
    std::copy(normals.y.begin(), normals.y.end(), c.inputs.lane(reg, 1));
    std::copy(normals.z.begin(), normals.z.end(), c.inputs.lane(reg, 2));
    std::fill_n(c.inputs.lane(reg, 3), vertices, 1.0f);
  }
  std::mt19937 rng(static_cast<std::mt19937::result_type>(kBenchSeed));
  std::uniform_real_distribution<float> value(-1.0f, 1.0f);
  for (int reg = 0; reg < c.constants.size(); ++reg) {
    for (int k = 0; k < 4; ++k) c.constants[reg][k] = value(rng);
  }
  return c;
}

void RunEngine(benchmark::State& state, const Program& program, const std::string& engine_name,
               std::optional<gl::GlPath> path) {
  const auto vertices = static_cast<std::size_t>(state.range(0));
  const Case c = MakeCase(program, vertices);
  EngineOptions options;
  if (path) {
    gl::GlOptions gl_options;
    gl_options.path = *path;
    options.settings.Set(gl_options);
  }
  Result<std::unique_ptr<Engine>> made = MakeEngine(engine_name, c.program, c.constants, options);
  if (!made) {
    state.SkipWithError(made.message().c_str());
    return;
  }
  const std::unique_ptr<Engine> engine = std::move(made).value();
  VertexArrays outputs = MakeOutputArrays(vertices, c.program);
  Status ran = engine->Run(c.inputs, outputs);  // warm: the driver compiles on first use
  for (auto _ : state) {
    if (!ran || !(ran = engine->Run(c.inputs, outputs))) {
      state.SkipWithError(ran.message().c_str());
      break;
    }
    benchmark::DoNotOptimize(outputs.lane(outputs.registers().front(), 0));
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(vertices));
}

[[maybe_unused]] const bool registered = [] {
  gl::RegisterGlEngine();
  namespace fs = std::filesystem;
  std::vector<fs::path> files;
  for (const fs::directory_entry& entry : fs::directory_iterator(fs::path(VS11_SOURCE_DIR) / "programs")) {
    if (entry.path().extension() == ".vsh") files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  std::vector<std::pair<std::string, std::shared_ptr<Program>>> programs;
  for (const fs::path& file : files) {
    ProgramForVerify loaded = LoadProgramForVerify(file);
    if (loaded.program) programs.emplace_back(file.stem().string(), std::make_shared<Program>(std::move(*loaded.program)));
  }
  const AssembleResult skinning = AssembleSource(kSkinningLoopVs20, "skinning_loop_vs_2_0.vsh", {});
  if (skinning.program) programs.emplace_back("skinning_loop_vs_2_0", std::make_shared<Program>(*skinning.program));
  for (const auto& [name, program] : programs) {
    struct Variant {
      const char* label;
      const char* engine;
      std::optional<gl::GlPath> path;
    };
    for (const Variant& variant : {Variant{"compute", "gl", gl::GlPath::kCompute},
                                   Variant{"transform-feedback", "gl", gl::GlPath::kTransformFeedback},
                                   Variant{"jit", "jit", std::nullopt}}) {
      benchmark::RegisterBenchmark(("BM_GlPath/" + name + "/" + variant.label).c_str(),
                                   [program, variant](benchmark::State& state) {
                                     RunEngine(state, *program, variant.engine, variant.path);
                                   })
          ->Arg(65536)
          ->Arg(1 << 20)
          ->UseRealTime()
          ->Unit(benchmark::kMillisecond);
    }
  }
  return true;
}();

}  // namespace
}  // namespace vs11::bench
