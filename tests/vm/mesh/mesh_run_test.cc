// vs11 run with meshes, .npy arrays and raw buffers, end to end through the built tool.
#include <cmath>
#include <cstring>
#include <filesystem>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "tests/run_tool.h"
#include "tests/vm/mesh/mesh_test_support.h"
#include "vm/asm/program_file.h"
#include "vm/core/atomic_file.h"
#include "vm/io/vertex_io.h"
#include "vm/mesh/mesh_io.h"
#include "vm/mesh/npy.h"

namespace vs11::mesh {
namespace {

namespace fs = std::filesystem;
using vs11::testing::kAssimpModels;
using vs11::testing::WriteText;

const std::string kPrograms = std::string(VS11_SOURCE_DIR) + "/programs/";
const std::string kSimpleSkin = std::string(kAssimpModels) + "/glTF2/simple_skin/simple_skin.gltf";
const std::string kBox = std::string(kAssimpModels) + "/glTF2/BoxTextured-glTF-Binary/BoxTextured.glb";

vs11::testing::CommandResult Vs11Run(const std::string& args) { return vs11::testing::RunVs11("run " + args); }

fs::path TempDir(const std::string& name) {
  fs::path dir = fs::temp_directory_path() / ("vs11_mesh_run_test_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

NpyArray ReadOutput(const fs::path& file) {
  Result<NpyArray> result = ReadNpy(file);
  EXPECT_TRUE(result.ok()) << result.message();
  return result.ok() ? *result : NpyArray{};
}

// Constants as --const flags: c0..c3 a view-projection, c4 the light, c5 the diffuse colour.
const double kViewProj[4][4] = {{0.9, 0.1, 0.0, 0.2}, {-0.1, 1.1, 0.2, -0.3}, {0.0, 0.2, -1.0, 2.0}, {0.0, 0.0, -1.0, 3.0}};
const double kLight[3] = {0.48, 0.6, 0.64};
const double kDiffuse[4] = {0.9, 0.7, 0.5, 1.0};

std::string Row(const double* v, int n) {
  std::string out;
  for (int i = 0; i < n; ++i) out += std::string(i ? "," : "") + vs11::FormatFloat(static_cast<float>(v[i]));
  return out;
}

std::string SkinningConstants() {
  std::string flags;
  for (int r = 0; r < 4; ++r) flags += " --const c" + std::to_string(r) + "=" + Row(kViewProj[r], 4);
  const double light[4] = {kLight[0], kLight[1], kLight[2], 0.0};
  flags += " --const c4=" + Row(light, 4) + " --const c5=" + Row(kDiffuse, 4);
  return flags;
}

using Matrix3x4 = std::array<std::array<double, 4>, 3>;

// programs/skinning.vsh in double precision over the mesh's own vertex data and `palette` (the
// float values the program reads), two bones a vertex.
void ExpectSkinnedOutputs(const Mesh& mesh, const std::vector<Matrix3x4>& palette, const fs::path& out_dir) {
  const NpyArray pos = ReadOutput(out_dir / "oPos.npy");
  const NpyArray od0 = ReadOutput(out_dir / "oD0.npy");
  ASSERT_EQ(pos.rows, mesh.vertex_count);
  ASSERT_EQ(od0.rows, mesh.vertex_count);
  for (std::size_t v = 0; v < mesh.vertex_count; ++v) {
    ASSERT_EQ(mesh.blend_weights[v][2], 0.0f) << "the program blends two bones; this vertex has more";
    double p[3] = {}, n[3] = {};
    for (int k = 0; k < 2; ++k) {
      const double w = mesh.blend_weights[v][k];
      const Matrix3x4& b = palette[static_cast<std::size_t>(mesh.blend_indices[v][k])];
      for (int r = 0; r < 3; ++r) {
        p[r] += w * (b[r][0] * mesh.positions[v][0] + b[r][1] * mesh.positions[v][1] + b[r][2] * mesh.positions[v][2] + b[r][3]);
        n[r] += w * (b[r][0] * mesh.normals[v][0] + b[r][1] * mesh.normals[v][1] + b[r][2] * mesh.normals[v][2]);
      }
    }
    const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    const double lambert = std::max(0.0, (n[0] * kLight[0] + n[1] * kLight[1] + n[2] * kLight[2]) / length);
    for (int r = 0; r < 4; ++r) {
      const double clip = kViewProj[r][0] * p[0] + kViewProj[r][1] * p[1] + kViewProj[r][2] * p[2] + kViewProj[r][3];
      EXPECT_NEAR(pos.values[v * 4 + r], clip, 1e-5 * (1 + std::abs(clip))) << "vertex " << v << " oPos." << r;
      EXPECT_NEAR(od0.values[v * 4 + r], kDiffuse[r] * lambert, 1e-5) << "vertex " << v << " oD0." << r;
    }
  }
}

Result<Mesh> LoadSkin() {
  MeshLoadOptions options;
  options.compute_normals = true;
  return LoadMesh(kSimpleSkin, options);
}

TEST(MeshRun, SkinningAtRestPoseMatchesDoublePrecisionSkinning) {
  Result<Mesh> loaded = LoadSkin();
  ASSERT_TRUE(loaded.ok()) << loaded.message();
  const fs::path out = TempDir("skin_rest");
  for (const char* engine : {"ref", "batch", "jit"}) {
    auto result = Vs11Run(kPrograms + "skinning.vsh --mesh " + kSimpleSkin +
                          " --compute-normals --blend-index-scale 3 --bone-palette c6" + SkinningConstants() +
                          " --engine " + engine + " --out-npy " + out.string());
    ASSERT_EQ(result.status, 0) << result.output;
    std::vector<Matrix3x4> palette;
    for (const Bone& bone : loaded->bones) {
      Matrix3x4 m;
      for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 4; ++c) m[r][c] = static_cast<float>(bone.skin[r][c]);
      }
      palette.push_back(m);
    }
    ExpectSkinnedOutputs(*loaded, palette, out);
  }
}

TEST(MeshRun, SkinningABentPoseMatchesDoublePrecisionSkinning) {
  Result<Mesh> loaded = LoadSkin();
  ASSERT_TRUE(loaded.ok()) << loaded.message();
  ASSERT_EQ(loaded->bones.size(), 2u);
  // Bone 0 a small shift, bone 1 bent 40 degrees about z around the joint at (0, 1, 0).
  const double angle = 40.0 * std::acos(-1.0) / 180.0, c = std::cos(angle), s = std::sin(angle);
  std::vector<Matrix3x4> palette = {
      Matrix3x4{{{1, 0, 0, 0.25}, {0, 1, 0, 0}, {0, 0, 1, -0.5}}},
      Matrix3x4{{{c, -s, 0, s}, {s, c, 0, 1 - c}, {0, 0, 1, 0}}},
  };
  std::string flags;
  for (std::size_t b = 0; b < palette.size(); ++b) {
    for (int r = 0; r < 3; ++r) {
      for (double& value : palette[b][r]) value = static_cast<float>(value);  // what the program reads
      flags += " --const c" + std::to_string(6 + 3 * b + r) + "=" + Row(palette[b][r].data(), 4);
    }
  }
  const fs::path out = TempDir("skin_bent");
  auto result = Vs11Run(kPrograms + "skinning.vsh --mesh " + kSimpleSkin + " --compute-normals --blend-index-scale 3" +
                        SkinningConstants() + flags + " --out-npy " + out.string());
  ASSERT_EQ(result.status, 0) << result.output;
  ExpectSkinnedOutputs(*loaded, palette, out);
}

TEST(MeshRun, MissingAttributeNamesTheDeclarationTheMeshAndAHint) {
  auto result = Vs11Run(kPrograms + "skinning.vsh --mesh " + kSimpleSkin);
  EXPECT_EQ(result.status, 1);
  EXPECT_NE(result.output.find("dcl_normal v3 needs normal, and " + kSimpleSkin + " has none"), std::string::npos)
      << result.output;
  EXPECT_NE(result.output.find("--compute-normals"), std::string::npos) << result.output;
  result = Vs11Run(kPrograms + "directional_light.vsh --mesh " + kBox + " --bind v1=color2");
  EXPECT_EQ(result.status, 1);
  EXPECT_NE(result.output.find("--bind v1=color2 needs color2"), std::string::npos) << result.output;
}

TEST(MeshRun, Dx8ProgramTakesAnExplicitBinding) {
  const fs::path dir = TempDir("dx8");
  WriteText(dir / "dx8.vsh", "vs.1.1\nmov oPos, v0\nmov oD0, v3\nmov oT0, v7\n");
  auto unbound = Vs11Run((dir / "dx8.vsh").string() + " --mesh " + kBox);
  EXPECT_EQ(unbound.status, 1);
  EXPECT_NE(unbound.output.find("--bind v0=position"), std::string::npos) << unbound.output;
  auto result = Vs11Run((dir / "dx8.vsh").string() + " --mesh " + kBox +
                        " --bind v0=position,v3=normal --bind v7=texcoord0 --out-npy " + (dir / "out").string());
  ASSERT_EQ(result.status, 0) << result.output;
  Result<Mesh> mesh = LoadMesh(kBox);
  ASSERT_TRUE(mesh.ok());
  const NpyArray pos = ReadOutput(dir / "out/oPos.npy"), d0 = ReadOutput(dir / "out/oD0.npy"), t0 = ReadOutput(dir / "out/oT0.npy");
  ASSERT_EQ(pos.rows, mesh->vertex_count);
  for (std::size_t v = 0; v < pos.rows; ++v) {
    for (int c = 0; c < 4; ++c) {
      EXPECT_EQ(pos.values[4 * v + c], mesh->positions[v][c]);
      EXPECT_EQ(d0.values[4 * v + c], mesh->normals[v][c]);
      EXPECT_EQ(t0.values[4 * v + c], mesh->texcoords[0][v][c]);
    }
  }
}

TEST(MeshRun, BrokenModelsGiveWarningsOrErrorsNeverACrash) {
  const std::string program =
      kPrograms + "directional_light.vsh --missing zeros --out-npy " + TempDir("broken").string() + " --mesh ";
  auto infinite = Vs11Run(program + kAssimpModels + "/glTF2/BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb");
  EXPECT_EQ(infinite.status, 0) << infinite.output;
  EXPECT_NE(infinite.output.find("warning: "), std::string::npos);
  EXPECT_NE(infinite.output.find("24 of 24 vertices have a NaN or infinite attribute"), std::string::npos) << infinite.output;
  auto normals = Vs11Run(program + kAssimpModels + "/glTF2/BoxBadNormals-glTF-Binary/BoxBadNormals.glb");
  EXPECT_EQ(normals.status, 0) << normals.output;
  EXPECT_NE(normals.output.find("8 normals are not of unit length (4 of them zero)"), std::string::npos) << normals.output;
  auto dropped = Vs11Run(program + kAssimpModels + "/glTF2/IndexOutOfRange/IndexOutOfRange.gltf");
  EXPECT_EQ(dropped.status, 0) << dropped.output;
  EXPECT_NE(dropped.output.find("out-of-range indices"), std::string::npos) << dropped.output;
  auto none = Vs11Run(program + kAssimpModels + "/glTF2/IndexOutOfRange/AllIndicesOutOfRange.gltf");
  EXPECT_EQ(none.status, 1) << none.output;
  EXPECT_NE(none.output.find("error: "), std::string::npos) << none.output;
  for (const char* name : {"badArray", "badNumber", "badObject", "badString", "badUint", "badExtension"}) {
    auto wrong = Vs11Run(program + kAssimpModels + "/glTF2/wrongTypes/" + name + ".gltf");
    EXPECT_EQ(wrong.status, 1) << wrong.output;
    EXPECT_NE(wrong.output.find("was not of type"), std::string::npos) << wrong.output;
  }
  auto oom = Vs11Run(program + kAssimpModels + "/invalid/OutOfMemory.off");
  EXPECT_EQ(oom.status, 1) << oom.output;
  EXPECT_NE(oom.output.find("more than a 309-byte file can hold"), std::string::npos) << oom.output;
}

// A pass-through program for the round trips.
fs::path WritePassThrough(const fs::path& dir) {
  WriteText(dir / "copy.vsh", "vs_1_1\ndcl_position v0\ndcl_color v1\nmov oPos, v0\nmov oD0, v1\n");
  return dir / "copy.vsh";
}

std::vector<float> AwkwardFloats(std::size_t count) {
  std::mt19937 random(11);
  std::uniform_int_distribution<std::uint32_t> bits;
  std::vector<float> values(count);
  for (float& v : values) {
    do {
      v = std::bit_cast<float>(bits(random));
    } while (!std::isfinite(v));  // every finite float, denormals and -0 included
  }
  values[0] = -0.0f;
  values[1] = std::numeric_limits<float>::denorm_min();
  values[2] = std::numeric_limits<float>::max();
  return values;
}

TEST(MeshRun, NpyRoundTripIsExactOnEveryEngine) {
  const fs::path dir = TempDir("npy_round_trip");
  const fs::path program = WritePassThrough(dir);
  NpyArray positions{1000, 4, AwkwardFloats(4000)};
  NpyArray colours{1000, 4, AwkwardFloats(4000)};
  std::reverse(colours.values.begin(), colours.values.end());
  ASSERT_TRUE(WriteFileAtomically(dir / "p.npy", FormatNpy(positions)).ok());
  ASSERT_TRUE(WriteFileAtomically(dir / "c.npy", FormatNpy(colours)).ok());
  for (const char* engine : {"ref", "batch", "jit"}) {
    const fs::path out = dir / engine;
    auto result = Vs11Run(program.string() + " --npy v0=" + (dir / "p.npy").string() + " --npy v1=" +
                          (dir / "c.npy").string() + " --engine " + engine + " --out-npy " + out.string());
    ASSERT_EQ(result.status, 0) << result.output;
    EXPECT_EQ(ReadWholeFile(out / "oPos.npy"), ReadWholeFile(dir / "p.npy")) << engine;
    EXPECT_EQ(ReadWholeFile(out / "oD0.npy"), ReadWholeFile(dir / "c.npy")) << engine;
  }
}

TEST(MeshRun, RawBufferRoundTripIsExactOnEveryEngine) {
  const fs::path dir = TempDir("raw_round_trip");
  const fs::path program = WritePassThrough(dir);
  const std::vector<float> floats = AwkwardFloats(8 * 777);  // stride 32: v0 at 0, v1 at 16
  vs11::testing::WriteBytes(dir / "in.bin", floats.data(), floats.size() * 4);
  for (const char* engine : {"ref", "batch", "jit"}) {
    const fs::path out = dir / (std::string(engine) + ".bin");
    auto result = Vs11Run(program.string() + " --buffer " + (dir / "in.bin").string() +
                          " --stride 32 --element v0=0:4 --element v1=16:4 --engine " + engine + " --out-buffer " +
                          out.string());
    ASSERT_EQ(result.status, 0) << result.output;
    EXPECT_NE(result.output.find("777 vertices, stride 32: oPos=0:4 oD0=16:4"), std::string::npos) << result.output;
    EXPECT_EQ(ReadWholeFile(out), ReadWholeFile(dir / "in.bin")) << engine;
  }
  // Three-float elements read (x, y, z, 1); a buffer that is not whole vertices is refused.
  auto short_elements = Vs11Run(program.string() + " --buffer " + (dir / "in.bin").string() +
                                " --stride 32 --element v0=4:3 --element v1=20:2 --out-npy " + (dir / "three").string());
  ASSERT_EQ(short_elements.status, 0) << short_elements.output;
  const NpyArray pos = ReadOutput(dir / "three/oPos.npy"), col = ReadOutput(dir / "three/oD0.npy");
  EXPECT_EQ(std::memcmp(&pos.values[4], &floats[9], 12), 0);
  EXPECT_EQ(pos.values[7], 1.0f);
  EXPECT_EQ(std::memcmp(&col.values[4], &floats[13], 8), 0);
  EXPECT_EQ(col.values[6], 0.0f);
  auto ragged = Vs11Run(program.string() + " --buffer " + (dir / "in.bin").string() + " --stride 36 --element v0=0:4");
  EXPECT_EQ(ragged.status, 1);
  EXPECT_NE(ragged.output.find("not a whole number of 36-byte vertices"), std::string::npos) << ragged.output;
  auto past = Vs11Run(program.string() + " --buffer " + (dir / "in.bin").string() + " --stride 32 --element v0=24:3");
  EXPECT_EQ(past.status, 2);  // the flags are wrong whatever the file holds: a usage error
  EXPECT_NE(past.output.find("past the 32-byte stride"), std::string::npos) << past.output;
}

TEST(MeshRun, OutMeshGlbCarriesOutputsAndKeepsInputPositions) {
  const fs::path dir = TempDir("out_glb");
  WriteText(dir / "uv.vsh", "vs_1_1\ndcl_position v0\ndcl_normal v1\ndcl_texcoord0 v2\n"
                            "def c0, 0.5, -2, 3, 1\nmul oPos, v0, c0\nmad oD0, v1, c0, c0.w\nmul oT1, v2, c0.yxzw\n");
  auto result = Vs11Run((dir / "uv.vsh").string() + " --mesh " + kBox + " --out-mesh " + (dir / "out.glb").string() +
                        " --out-npy " + (dir / "npy").string());
  ASSERT_EQ(result.status, 0) << result.output;
  Result<Mesh> input = LoadMesh(kBox);
  MeshLoadOptions raw;
  raw.transform_to_world = false;
  Result<Mesh> output = LoadMesh(dir / "out.glb", raw);
  ASSERT_TRUE(input.ok() && output.ok()) << output.message();
  const NpyArray d0 = ReadOutput(dir / "npy/oD0.npy"), t1 = ReadOutput(dir / "npy/oT1.npy");
  ASSERT_EQ(output->vertex_count, input->vertex_count);
  EXPECT_EQ(output->indices, input->indices);
  ASSERT_FALSE(output->colors[0].empty());
  ASSERT_FALSE(output->texcoords[0].empty());
  for (std::size_t v = 0; v < output->vertex_count; ++v) {
    for (int c = 0; c < 3; ++c) EXPECT_EQ(output->positions[v][c], input->positions[v][c]);
    for (int c = 0; c < 4; ++c) EXPECT_EQ(output->colors[0][v][c], d0.values[4 * v + c]);
    // glTF flips v (Assimp reads v' = 1 - v and writes it back); both ways are exact for these values.
    EXPECT_EQ(output->texcoords[0][v][0], t1.values[4 * v]);
    EXPECT_FLOAT_EQ(output->texcoords[0][v][1], t1.values[4 * v + 1]);
  }
  const std::optional<std::string> bytes = ReadWholeFile(dir / "out.glb");
  ASSERT_TRUE(bytes);
  EXPECT_NE(bytes->find("\"vs11\":\"positions and normals are the input mesh's"), std::string::npos);
  EXPECT_NE(bytes->find("oT1.xy -> UV set 0"), std::string::npos);
}

TEST(MeshRun, OutMeshPlyCarriesClampedColoursAndSaysSo) {
  const fs::path dir = TempDir("out_ply");
  const std::string wuson = std::string(kAssimpModels) + "/PLY/Wuson.ply";
  auto result = Vs11Run(kPrograms + "directional_light.vsh --mesh " + wuson +
                        " --const c0=1,0,0,0 --const c1=0,1,0,0 --const c2=0,0,1,0 --const c3=0,0,0,1"
                        " --const c4=1,0,0,0 --const c5=0,1,0,0 --const c6=0,0,1,0 --const c7=0,0.6,0.8,0"
                        " --const c8=0,0,5,1 --const c9=1.5,0.8,0.6,1 --const c10=0,0,0,0 --const c11=-0.2,0,0,0"
                        " --const c12=0,0,0,0 --out-mesh " +
                        (dir / "lit.ply").string() + " --out-npy " + (dir / "npy").string());
  ASSERT_EQ(result.status, 0) << result.output;
  const std::optional<std::string> bytes = ReadWholeFile(dir / "lit.ply");
  ASSERT_TRUE(bytes);
  EXPECT_NE(bytes->find("comment vs11: positions and normals are the input mesh's"), std::string::npos);
  EXPECT_NE(bytes->find("comment vs11: PLY colours: clamped to [0, 1], 8-bit"), std::string::npos);
  MeshLoadOptions raw;
  raw.transform_to_world = false;
  Result<Mesh> output = LoadMesh(dir / "lit.ply", raw);
  ASSERT_TRUE(output.ok()) << output.message();
  const NpyArray d0 = ReadOutput(dir / "npy/oD0.npy");
  ASSERT_EQ(output->vertex_count, d0.rows);
  ASSERT_FALSE(output->colors[0].empty());
  for (std::size_t v = 0; v < d0.rows; ++v) {
    for (int c = 0; c < 4; ++c) {
      EXPECT_NEAR(output->colors[0][v][c], std::clamp(d0.values[4 * v + c], 0.0f, 1.0f), 1.0 / 255) << v;
    }
  }
}

}  // namespace
}  // namespace vs11::mesh
