// Mesh loading beside engine runs, from several threads at once: LoadMesh and LoadMeshFromMemory
// may be called from several threads (vm/mesh/mesh_io.h), each load forking its Assimp child
// (vm/mesh/mesh_sandbox.h) while other threads run engines. Every mesh must equal a load on one
// thread, every engine result the same run on one thread, bit for bit. CI's ThreadSanitizer stage
// (.ci/tsan) runs this.
#include <bit>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/run_threads.h"
#include "tests/vm/mesh/mesh_test_support.h"
#include "vm/asm/program_file.h"
#include "vm/engines/engine_factory.h"
#include "vm/mesh/mesh_io.h"
#include "vm/mesh/vertex_binding.h"

namespace vs11::mesh {
namespace {

namespace fs = std::filesystem;
using vs11::testing::kAssimpModels;
using vs11::testing::RunOnThreads;

const fs::path kBox = fs::path(kAssimpModels) / "glTF2/BoxTextured-glTF-Binary/BoxTextured.glb";
const fs::path kSkin = fs::path(kAssimpModels) / "glTF2/simple_skin/simple_skin.gltf";

bool SameBits(const std::vector<Vec4f>& a, const std::vector<Vec4f>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(Vec4f)) == 0);
}

void ExpectSameMesh(const Result<Mesh>& loaded, const Mesh& alone, const std::string& context) {
  ASSERT_TRUE(loaded.ok()) << context << ": " << loaded.message();
  const Mesh& mesh = *loaded;
  EXPECT_EQ(mesh.vertex_count, alone.vertex_count) << context;
  EXPECT_TRUE(SameBits(mesh.positions, alone.positions)) << context;
  EXPECT_TRUE(SameBits(mesh.normals, alone.normals)) << context;
  EXPECT_TRUE(SameBits(mesh.texcoords[0], alone.texcoords[0])) << context;
  EXPECT_TRUE(SameBits(mesh.blend_weights, alone.blend_weights)) << context;
  EXPECT_TRUE(SameBits(mesh.blend_indices, alone.blend_indices)) << context;
  EXPECT_EQ(mesh.indices, alone.indices) << context;
  EXPECT_EQ(mesh.warnings, alone.warnings) << context;
}

// The box's vertices through programs/directional_light.vsh, bound by its declarations.
std::vector<float> LightBox(const Mesh& box, const Program& program, std::string kind) {
  std::vector<RegisterBinding> bindings;
  EXPECT_EQ(ResolveBindings(program, {}, bindings).message(), "");
  RegisterData registers;
  EXPECT_EQ(BindMesh(box, bindings, {}, registers).message(), "");
  std::vector<int> used;
  for (const auto& [reg, values] : registers) used.push_back(reg);
  VertexArrays inputs = MakeInputArrays(box.vertex_count, used);
  for (const auto& [reg, values] : registers) {
    for (int c = 0; c < 4; ++c) {
      for (std::size_t i = 0; i < values.size(); ++i) inputs.lane(reg, c)[i] = values[i][c];
    }
  }
  ConstantBank constants;
  for (int reg = 0; reg < constants.size(); ++reg) constants[reg] = {0.1f * reg, 0.5f, -0.25f * reg, 1.0f};
  VertexArrays outputs = MakeOutputArrays(box.vertex_count, program);
  EXPECT_EQ(MakeEngine(kind, program, constants).value()->Run(inputs, outputs).message(), "");
  std::vector<float> flat;
  for (int slot : outputs.registers()) {
    for (int c = 0; c < 4; ++c) flat.insert(flat.end(), outputs.lane(slot, c), outputs.lane(slot, c) + box.vertex_count);
  }
  return flat;
}

TEST(MeshConcurrent, LoadsFromSeveralThreadsBesideEngineRunsMatchOneThread) {
  const Result<Mesh> box = LoadMesh(kBox);
  const Result<Mesh> skin = LoadMesh(kSkin);
  ASSERT_TRUE(box.ok()) << box.message();
  ASSERT_TRUE(skin.ok()) << skin.message();
  const std::optional<std::string> glb_bytes = ReadWholeFile(kBox);
  ASSERT_TRUE(glb_bytes);
  const std::vector<std::uint8_t> glb(glb_bytes->begin(), glb_bytes->end());
  LoadedProgram light = LoadProgram(fs::path(VS11_SOURCE_DIR) / "programs/directional_light.vsh");
  ASSERT_TRUE(light.program) << light.diagnostics.ToString();
  const std::vector<float> lit = LightBox(*box, *light.program, "jit");

  // Threads 0-2 load (files, and bytes), threads 3-4 run engines on the mesh loaded above.
  constexpr int kRounds = 3;
  RunOnThreads(5, [&](int t) {
    for (int round = 0; round < kRounds; ++round) {
      const std::string context = "thread " + std::to_string(t) + " round " + std::to_string(round);
      if (t == 0) ExpectSameMesh(LoadMesh(kBox), *box, "box, " + context);
      if (t == 1) ExpectSameMesh(LoadMesh(kSkin), *skin, "skin, " + context);
      if (t == 2) ExpectSameMesh(LoadMeshFromMemory(glb, "glb"), *box, "box bytes, " + context);
      if (t >= 3) {
        const std::string kind = t == 3 ? "jit" : "batch";
        EXPECT_EQ(LightBox(*box, *light.program, kind), lit) << kind << ", " << context;
      }
    }
  });
}

}  // namespace
}  // namespace vs11::mesh
