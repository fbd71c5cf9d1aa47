// Meshes: loading through Assimp, and the paper's program (programs/sh9_irradiance.vsh, the normal
// in v0, Table 1 constants at c0..c6) over every vertex normal with each engine.
//   BM_MeshLoad/<model>            mesh::LoadMesh, transforms applied (the `vs11 run --mesh` load)
//   BM_MeshLoadAllModels           every assimp-testmodels file with normals, loaded once each
//   BM_MeshRun/<model>/<engine>    one Engine::Run over the mesh's normals, one thread
// <model> is a file of Debian's assimp-testmodels or sphere_1M, a generated UV sphere of
// 1000 x 1000 = 1,000,000 vertices written once per process as binary PLY to the temp folder.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "bench/bench_common.h"
#include "vm/core/machine.h"
#include "vm/engines/engine_factory.h"
#include "vm/mesh/mesh_io.h"

namespace vs11::bench {
namespace {

namespace fs = std::filesystem;

const char* const kModels = "/usr/share/assimp/models";

struct BenchModel {
  const char* name;
  const char* path;  // under kModels, or empty for the generated sphere
};
const BenchModel kBenchModels[] = {
    {"Wuson.ply", "PLY/Wuson.ply"},
    {"spider.obj", "OBJ/spider.obj"},
    {"COLLADA.dae", "Collada/COLLADA.dae"},
    {"fromtruespace_bin32.x", "X/fromtruespace_bin32.x"},
    {"human.zae", "Collada/human.zae"},
    {"2CylinderEngine.glb", "glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb"},
    {"yxa_1.blend", "BLEND/yxa_1.blend"},
    {"SuzanneSubdiv_252.blend", "BLEND/SuzanneSubdiv_252.blend"},
    {"sphere_1M", ""},
};

// A UV sphere, rows x columns vertices (normal = position), two triangles per quad, as binary PLY.
fs::path GeneratedSphere() {
  static const fs::path path = [] {
    constexpr int kRows = 1000, kColumns = 1000;
    const fs::path file = fs::temp_directory_path() / "vs11_bench_sphere_1M.ply";
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    const long faces = 2L * (kRows - 1) * (kColumns - 1);
    out << "ply\nformat binary_little_endian 1.0\nelement vertex " << kRows * kColumns
        << "\nproperty float x\nproperty float y\nproperty float z\nproperty float nx\nproperty float ny\n"
           "property float nz\nelement face "
        << faces << "\nproperty list uchar int vertex_indices\nend_header\n";
    const double pi = std::acos(-1.0);
    for (int r = 0; r < kRows; ++r) {
      const double theta = pi * (r + 0.5) / kRows;
      for (int c = 0; c < kColumns; ++c) {
        const double phi = 2 * pi * c / kColumns;
        const float p[3] = {static_cast<float>(std::sin(theta) * std::cos(phi)),
                            static_cast<float>(std::sin(theta) * std::sin(phi)), static_cast<float>(std::cos(theta))};
        out.write(reinterpret_cast<const char*>(p), sizeof p);
        out.write(reinterpret_cast<const char*>(p), sizeof p);
      }
    }
    for (int r = 0; r + 1 < kRows; ++r) {
      for (int c = 0; c + 1 < kColumns; ++c) {
        const int a = r * kColumns + c, b = a + 1, d = a + kColumns, e = d + 1;
        const unsigned char three = 3;
        const int first[3] = {a, d, b}, second[3] = {b, d, e};
        out.write(reinterpret_cast<const char*>(&three), 1);
        out.write(reinterpret_cast<const char*>(first), sizeof first);
        out.write(reinterpret_cast<const char*>(&three), 1);
        out.write(reinterpret_cast<const char*>(second), sizeof second);
      }
    }
    return file;
  }();
  return path;
}

fs::path ModelPath(const BenchModel& model) {
  return *model.path == '\0' ? GeneratedSphere() : fs::path(kModels) / model.path;
}

const mesh::Mesh& CachedMesh(const BenchModel& model) {
  static std::map<std::string, mesh::Mesh> cache;
  auto it = cache.find(model.name);
  if (it == cache.end()) {
    Result<mesh::Mesh> result = mesh::LoadMesh(ModelPath(model));
    if (!result.ok() || result->normals.empty()) {
      std::fprintf(stderr, "vs11_bench: %s: %s\n", model.name, result.ok() ? "no normals" : result.message().c_str());
      std::abort();
    }
    it = cache.emplace(model.name, std::move(result).value()).first;
  }
  return it->second;
}

void BM_MeshLoad(benchmark::State& state, const BenchModel& model) {
  const fs::path path = ModelPath(model);
  std::size_t vertices = 0;
  for (auto _ : state) {
    Result<mesh::Mesh> result = mesh::LoadMesh(path);
    if (!result.ok()) {
      state.SkipWithError(result.message().c_str());
      return;
    }
    vertices = result->vertex_count;
    benchmark::DoNotOptimize(result->positions.data());
  }
  state.counters["vertices"] = static_cast<double>(vertices);
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * vertices));
}

void BM_MeshLoadAllModels(benchmark::State& state) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::recursive_directory_iterator(kModels)) {
    if (!entry.is_regular_file() || !mesh::IsMeshFileExtension(entry.path().extension().string())) continue;
    Result<mesh::Mesh> result = mesh::LoadMesh(entry.path());
    if (result.ok() && !result->normals.empty()) files.push_back(entry.path());
  }
  std::size_t vertices = 0;
  for (auto _ : state) {
    vertices = 0;
    for (const fs::path& file : files) vertices += mesh::LoadMesh(file)->vertex_count;
  }
  state.counters["models"] = static_cast<double>(files.size());
  state.counters["vertices"] = static_cast<double>(vertices);
}

void BM_MeshRun(benchmark::State& state, const BenchModel& model, std::string kind) {
  const mesh::Mesh& mesh = CachedMesh(model);
  const vs11::ProgramForVerify loaded = LoadBenchProgram(ProgramPath("sh9_irradiance.vsh"));
  const Program& program = *loaded.program;
  const ConstantBank bank = Table1Bank(vs11::PackTable1(BenchCoefficients()));
  const std::size_t count = mesh.vertex_count;
  const int v0[] = {0};
  VertexArrays inputs = MakeInputArrays(count, v0);
  for (int c = 0; c < 4; ++c) {
    float* lane = inputs.lane(0, c);
    for (std::size_t i = 0; i < count; ++i) lane[i] = mesh.normals[i][c];
  }
  VertexArrays outputs = MakeOutputArrays(count, program);
  std::unique_ptr<Engine> engine = MakeEngine(kind, program, bank, EngineOptions{.threads = 1}).value();
  for (auto _ : state) {
    if (const Status ran = engine->Run(inputs, outputs); !ran) {
      state.SkipWithError(ran.message().c_str());
      break;
    }
    benchmark::DoNotOptimize(outputs.lane(static_cast<int>(OutputSlot::kDiffuse), 0));
    benchmark::ClobberMemory();
  }
  state.counters["vertices"] = static_cast<double>(count);
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * count));
}

[[maybe_unused]] const bool kRegistered = [] {
  for (const BenchModel& model : kBenchModels) {
    benchmark::RegisterBenchmark((std::string("BM_MeshLoad/") + model.name).c_str(), BM_MeshLoad, model)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
  }
  benchmark::RegisterBenchmark("BM_MeshLoadAllModels", BM_MeshLoadAllModels)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);
  for (const BenchModel& model : kBenchModels) {
    for (std::string kind : {"ref", "batch", "jit"}) {
      benchmark::RegisterBenchmark(
          (std::string("BM_MeshRun/") + model.name + "/" + std::string(kind)).c_str(), BM_MeshRun, model, kind)
          ->Unit(benchmark::kMillisecond);
    }
  }
  return true;
}();

}  // namespace
}  // namespace vs11::bench
