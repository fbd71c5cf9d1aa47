#include "vm/mesh/mesh_io.h"

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "tests/vm/mesh/mesh_test_support.h"
#include "vm/mesh/mesh_sandbox.h"

namespace vs11::mesh {
namespace {

namespace fs = std::filesystem;
using vs11::testing::kAssimpModels;

fs::path TempDir(const std::string& name) {
  fs::path dir = fs::temp_directory_path() / ("vs11_mesh_io_test_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

TEST(LoadMesh, NodeTransformMovesPositionsAndNormalsByItsInverseTranspose) {
  const float normal[3] = {0.70710678f, 0.70710678f, 0.0f};
  fs::path file = vs11::testing::WriteGltfTriangle(TempDir("transform"), normal, "[2, 1, 1]", "[1, 2, 3]");
  Result<Mesh> result = LoadMesh(file);
  ASSERT_TRUE(result.ok()) << result.message();
  const Mesh& mesh = *result;
  ASSERT_EQ(mesh.vertex_count, 3u);
  EXPECT_EQ(mesh.indices, (std::vector<std::uint32_t>{0, 1, 2}));
  EXPECT_EQ(mesh.positions[1], (Vec4f{3, 2, 3, 1}));
  // inverse transpose of diag(2, 1, 1) is diag(1/2, 1, 1): (1, 1, 0) -> (1/2, 1, 0) -> (1, 2, 0)/sqrt 5
  EXPECT_NEAR(mesh.normals[0][0], 1 / std::sqrt(5.0), 1e-6);
  EXPECT_NEAR(mesh.normals[0][1], 2 / std::sqrt(5.0), 1e-6);
  EXPECT_EQ(mesh.normals[0][3], 1.0f);
  ASSERT_EQ(mesh.parts.size(), 1u);
  EXPECT_TRUE(mesh.parts[0].transformed);
  EXPECT_EQ(mesh.parts[0].transform[0][3], 1.0);
  EXPECT_EQ(mesh.parts[0].transform[0][0], 2.0);

  MeshLoadOptions raw;
  raw.transform_to_world = false;
  result = LoadMesh(file, raw);
  ASSERT_TRUE(result.ok()) << result.message();
  EXPECT_EQ(result->positions[1], (Vec4f{1, 0, 0, 1}));
  EXPECT_FALSE(result->parts[0].transformed);
}

TEST(LoadMesh, MirroringTransformKeepsNormalsOutward) {
  const float normal[3] = {0, 0, 1};
  fs::path file = vs11::testing::WriteGltfTriangle(TempDir("mirror"), normal, "[1, 1, -1]", "[0, 0, 0]");
  Result<Mesh> result = LoadMesh(file);
  ASSERT_TRUE(result.ok()) << result.message();
  EXPECT_EQ(result->normals[0], (Vec4f{0, 0, -1, 1}));
}

TEST(LoadMesh, SkinnedGltfHasBonesWeightsAndComputedNormals) {
  const fs::path file = fs::path(kAssimpModels) / "glTF2/simple_skin/simple_skin.gltf";
  Result<Mesh> plain = LoadMesh(file);
  ASSERT_TRUE(plain.ok()) << plain.message();
  EXPECT_TRUE(plain->normals.empty());
  MeshLoadOptions options;
  options.compute_normals = true;
  Result<Mesh> result = LoadMesh(file, options);
  ASSERT_TRUE(result.ok()) << result.message();
  const Mesh& mesh = *result;
  EXPECT_EQ(mesh.vertex_count, 10u);
  EXPECT_EQ(mesh.indices.size(), 24u);
  EXPECT_EQ(mesh.normals.size(), 10u);
  EXPECT_EQ(mesh.bones.size(), 2u);
  ASSERT_EQ(mesh.blend_weights.size(), 10u);
  for (std::size_t v = 0; v < mesh.vertex_count; ++v) {
    const Vec4f& w = mesh.blend_weights[v];
    EXPECT_NEAR(w[0] + w[1] + w[2] + w[3], 1.0f, 1e-6) << v;
    EXPECT_GE(w[0], w[1]);
    EXPECT_LT(mesh.blend_indices[v][0], 2.0f);
  }
  EXPECT_TRUE(mesh.parts[0].skinned);
  EXPECT_FALSE(mesh.parts[0].transformed);
  EXPECT_TRUE(mesh.warnings.empty());
}

TEST(LoadMesh, JoinsTheMeshesOfAScene) {
  Result<Mesh> result = LoadMesh(fs::path(kAssimpModels) / "glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb");
  ASSERT_TRUE(result.ok()) << result.message();
  const Mesh& mesh = *result;
  ASSERT_GT(mesh.parts.size(), 1u);
  std::size_t vertices = 0, indices = 0;
  for (const MeshPart& part : mesh.parts) {
    EXPECT_EQ(part.first_vertex, vertices);
    EXPECT_EQ(part.first_index, indices);
    vertices += part.vertex_count;
    indices += part.index_count;
    for (std::size_t i = part.first_index; i < part.first_index + part.index_count; ++i) {
      ASSERT_GE(mesh.indices[i], part.first_vertex);
      ASSERT_LT(mesh.indices[i], part.first_vertex + part.vertex_count);
    }
  }
  EXPECT_EQ(vertices, mesh.vertex_count);
  EXPECT_EQ(indices, mesh.indices.size());
}

TEST(LoadMesh, InfinitePositionsAreCountedInAWarning) {
  Result<Mesh> result = LoadMesh(fs::path(kAssimpModels) / "glTF2/BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb");
  ASSERT_TRUE(result.ok()) << result.message();
  EXPECT_GT(result->nonfinite_vertex_count, 0u);
  ASSERT_FALSE(result->warnings.empty());
  EXPECT_NE(result->warnings[0].find("NaN or infinite"), std::string::npos) << result->warnings[0];
}

TEST(LoadMesh, IndicesOutOfRangeDropTrianglesWithAWarningOrFailWhenNoneIsLeft) {
  const fs::path dir = fs::path(kAssimpModels) / "glTF2/IndexOutOfRange";
  Result<Mesh> some = LoadMesh(dir / "IndexOutOfRange.gltf");
  ASSERT_TRUE(some.ok()) << some.message();
  EXPECT_EQ(some->indices.size(), 33u);  // 12 triangles in the file, one refers past the 24 vertices
  ASSERT_FALSE(some->warnings.empty());
  EXPECT_NE(some->warnings[0].find("out-of-range indices"), std::string::npos) << some->warnings[0];
  const fs::path all = dir / "AllIndicesOutOfRange.gltf";
  Result<Mesh> none = LoadMesh(all);
  EXPECT_FALSE(none.ok());
  EXPECT_NE(none.message().find(all.string()), std::string::npos) << none.message();
}

TEST(LoadMesh, BadNormalsAreCountedInAWarning) {
  Result<Mesh> result = LoadMesh(fs::path(kAssimpModels) / "glTF2/BoxBadNormals-glTF-Binary/BoxBadNormals.glb");
  ASSERT_TRUE(result.ok()) << result.message();
  ASSERT_EQ(result->warnings.size(), 1u);
  EXPECT_EQ(result->warnings[0].rfind("8 normals are not of unit length (4 of them zero)", 0), 0u)
      << result->warnings[0];
  EXPECT_EQ(result->normals[0], (Vec4f{0, 0, 0, 1}));  // zero stays zero, never NaN
  const Vec4f& short_normal = result->normals[4];  // (0, -0.1, 0) in the file, under a rotation
  EXPECT_NEAR(std::hypot(short_normal[0], short_normal[1], short_normal[2]), 1.0, 1e-6);
}

// vs11 run --compute-normals: the zero facet normals of Debian's Wuson.stl are replaced too.
TEST(LoadMesh, ComputeNormalsReplacesZeroNormalsOfTheFile) {
  MeshLoadOptions options;
  options.compute_normals = true;
  Result<Mesh> result = LoadMesh(fs::path(kAssimpModels) / "STL/Wuson.stl", options);
  ASSERT_TRUE(result.ok()) << result.message();
  ASSERT_EQ(result->normals.size(), 11196u);
  for (std::size_t i = 0; i < result->normals.size(); ++i) {
    const Vec4f& n = result->normals[i];
    ASSERT_NEAR(std::hypot(n[0], n[1], n[2]), 1.0, 1e-6) << "vertex " << i;
  }
}

// Assimp-testmodels' OBJ/point_cloud.obj: three points with normals, no face. With
// aiProcess_ForceGenNormals, Assimp 5.2 freed such a mesh's normals and left the pointer, and the
// loader read freed memory (fuzz_mesh's heap-use-after-free in CI's ASan stage, on this file as a
// seed). Loaded in this process too, so that AddressSanitizer sees any read of Assimp's arrays.
TEST(LoadMesh, ComputeNormalsKeepsThePointNormalsOfAPointCloud) {
  const fs::path file = fs::path(kAssimpModels) / "OBJ/point_cloud.obj";
  const Result<Mesh> plain = LoadMesh(file);
  ASSERT_TRUE(plain.ok()) << plain.message();
  ASSERT_EQ(plain->normals.size(), 3u);
  EXPECT_TRUE(plain->indices.empty());
  std::ifstream in(file, std::ios::binary);
  const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (const bool repair : {false, true}) {
    MeshLoadOptions options;
    options.compute_normals = true;
    options.repair_normals = repair;
    const Result<Mesh> sandboxed = LoadMesh(file, options);
    const Result<Mesh> in_process = internal::LoadMeshFromMemoryInProcess(bytes, "obj", options, [](internal::LoadStage) {});
    for (const Result<Mesh>* result : {&sandboxed, &in_process}) {
      ASSERT_TRUE(result->ok()) << result->message();
      EXPECT_EQ((*result)->normals, plain->normals);  // points have no normal to compute
    }
  }
}

// Computed normals move with the part as the file's do (mesh_io.h): under a mirroring node the
// triangle's computed normal is the one the file's matching normal becomes.
TEST(LoadMesh, ComputedNormalsFollowTheNodeTransformAsTheFilesDo) {
  const float file_normal[3] = {0, 0, 1};  // the triangle's counter-clockwise side
  const float zero[3] = {0, 0, 0};
  for (const char* scale : {"[1, 1, 1]", "[1, 1, -1]", "[2, 0.5, 3]"}) {
    const Result<Mesh> from_file = LoadMesh(vs11::testing::WriteGltfTriangle(TempDir("file"), file_normal, scale, "[0, 0, 0]"));
    MeshLoadOptions options;
    options.repair_normals = true;
    const Result<Mesh> computed =
        LoadMesh(vs11::testing::WriteGltfTriangle(TempDir("zero"), zero, scale, "[0, 0, 0]"), options);
    ASSERT_TRUE(from_file.ok() && computed.ok()) << from_file.message() << computed.message();
    EXPECT_EQ(computed->normals, from_file->normals) << scale;
    ASSERT_EQ(computed->warnings.size(), 1u);
    EXPECT_EQ(computed->warnings[0].rfind("3 of 3 vertices have no usable normal", 0), 0u) << computed->warnings[0];
  }
}

TEST(LoadMesh, WrongJsonTypesAreErrors) {
  for (const char* name : {"badArray", "badNumber", "badObject", "badString", "badUint", "badExtension"}) {
    const fs::path file = fs::path(kAssimpModels) / "glTF2/wrongTypes" / (std::string(name) + ".gltf");
    Result<Mesh> result = LoadMesh(file);
    EXPECT_FALSE(result.ok()) << name;
    EXPECT_NE(result.message().find("was not of type"), std::string::npos) << result.message();
  }
}

TEST(LoadMesh, MissingEmptyAndOversizedFilesAreRefused) {
  const fs::path dir = TempDir("refused");
  Result<Mesh> missing = LoadMesh(dir / "none.obj");
  ASSERT_FALSE(missing.ok());
  EXPECT_EQ(missing.error().code, DiagnosticCode::kCannotReadFile);
  EXPECT_EQ(missing.message(), (dir / "none.obj").string() + ": no such file");
  vs11::testing::WriteText(dir / "empty.obj", "");
  EXPECT_EQ(LoadMesh(dir / "empty.obj").message(), (dir / "empty.obj").string() + ": the file is empty");
  // A sparse file one byte over the limit: refused from its size, never read.
  const fs::path big = dir / "big.obj";
  vs11::testing::WriteText(big, "v 0 0 0\n");
  fs::resize_file(big, kMaxMeshFileBytes + 1);
  Result<Mesh> oversized = LoadMesh(big);
  ASSERT_FALSE(oversized.ok());
  EXPECT_EQ(oversized.error().code, DiagnosticCode::kCannotReadFile);
  EXPECT_NE(oversized.message().find("limit"), std::string::npos) << oversized.message();
  vs11::testing::WriteText(dir / "garbage.obj", "this is not a mesh\n");
  EXPECT_FALSE(LoadMesh(dir / "garbage.obj").ok());
}

TEST(LoadMesh, FromMemoryReadsAnObj) {
  const std::string obj = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1 4//1\n";
  Result<Mesh> result = LoadMeshFromMemory(
      {reinterpret_cast<const std::uint8_t*>(obj.data()), obj.size()}, "obj");
  ASSERT_TRUE(result.ok()) << result.message();
  EXPECT_EQ(result->indices.size(), 6u);  // the quad triangulated
  EXPECT_EQ(result->normals.size(), result->vertex_count);
}


// fuzz_mesh: an OFF file whose faces are no polygons while Assimp's reader flags the mesh as
// holding polygons made aiProcess_Triangulate abort (ai_assert). The flags are rebuilt from the
// faces before post-processing.
TEST(LoadMesh, FuzzerFoundOffWithAPolygonFlagAndNoPolygonLoads) {
  const std::filesystem::path file =
      std::filesystem::path(VS11_SOURCE_DIR) / "tests/fuzz/seeds/fuzz_mesh/off_polygon_flag_without_polygons.off";
  std::ifstream in(file, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_FALSE(bytes.empty());
  Result<Mesh> result = LoadMeshFromMemory({reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()}, "");
  if (result.ok()) {
    for (std::uint32_t index : result->indices) EXPECT_LT(index, result->vertex_count);
  } else {
    EXPECT_FALSE(result.message().empty());
  }
}


// fuzz_mesh: PLY headers checked before Assimp reads the file. An element without properties and
// no end_header made Assimp's PLY reader loop without end; an "element" line without a space made
// the check itself form a pointer from npos (UBSan).
TEST(LoadMesh, FuzzerFoundPlyHeadersAreRefusedAtOnce) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"ply_element_without_property.ply", "no PLY end_header"},
      {"ply_element_without_count.ply", "PLY header line 'element' has no element count"}};
  for (const auto& [name, reason] : cases) {
    Result<Mesh> result = LoadMesh(std::filesystem::path(VS11_SOURCE_DIR) / "tests/fuzz/seeds/fuzz_mesh" / name);
    EXPECT_FALSE(result.ok()) << name;
    EXPECT_NE(result.message().find(reason), std::string::npos) << result.message();
  }
}

}  // namespace
}  // namespace vs11::mesh
