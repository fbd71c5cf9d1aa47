// irrmap --mesh's loader: vertices whose normal the file omits, or gives as zero, get computed
// smooth normals with a warning (a mesh is lit, never drawn black for want of normals), and the
// file's usable normals keep their bits.
#include "irradiance/mesh_input/mesh_geometry_io.h"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "irradiance/io/environments.h"
#include "irradiance/report/paper_program.h"
#include "irradiance/sh/ground_truth.h"
#include "irradiance/sh/sh9.h"
#include "irradiance/sh/sh_projection.h"
#include "tests/run_tool.h"
#include "vm/mesh/mesh_io.h"

namespace vs11::irradiance {
namespace {

using ::testing::HasSubstr;

// assimp-testmodels' Wuson as binary STL (every facet normal zero) and as PLY (with normals).
constexpr const char* kWusonStl = "/usr/share/assimp/models/STL/Wuson.stl";
constexpr const char* kWusonPly = "/usr/share/assimp/models/PLY/Wuson.ply";
constexpr std::size_t kWusonStlVertices = 11196;
// Normals are normalised in double and rounded to float.
constexpr double kUnitTolerance = 1e-6;

std::string AllWarnings(const std::vector<std::string>& warnings) {
  std::string all;
  for (const std::string& warning : warnings) all += warning + "\n";
  return all;
}

TEST(LoadMeshGeometry, ZeroNormalsOfAnStlAreComputedWithAWarning) {
  MeshGeometry geometry;
  std::vector<std::string> warnings;
  ASSERT_EQ(LoadMeshGeometry(kWusonStl, geometry, warnings).message(), "");
  ASSERT_EQ(geometry.normals.size(), kWusonStlVertices);
  for (std::size_t i = 0; i < geometry.normals.size(); ++i) {
    ASSERT_NEAR(glm::length(glm::dvec3(geometry.normals[i])), 1.0, kUnitTolerance) << "vertex " << i;
  }
  EXPECT_THAT(AllWarnings(warnings),
              HasSubstr(std::string(kWusonStl) + ": 11196 of 11196 vertices have no usable normal (none, zero or not "
                        "finite) in the file: computed smooth normals for them"));
  EXPECT_THAT(AllWarnings(warnings), ::testing::Not(HasSubstr("of them zero")));
}

// The sky lights the STL as it lights any closed mesh: the mean irradiance over its vertices is
// near the sky's mean over all normals (pi times its mean radiance), not black.
TEST(LoadMeshGeometry, AnStlWithZeroNormalsIsLitBySky) {
  MeshGeometry geometry;
  std::vector<std::string> warnings;
  ASSERT_EQ(LoadMeshGeometry(kWusonStl, geometry, warnings).message(), "");
  Result<PaperProgram> program = PaperProgram::Load();
  ASSERT_TRUE(program) << program.message();
  const CubeMap sky = *MakeBuiltinEnvironment("sky", 8);
  MeshLightingOptions options;
  options.truth_vertex_limit = 1;  // the program's irradiance alone
  options.panel_size = 32;
  const Result<MeshLighting> lit = LightMesh(geometry, *program, PackTable1(ProjectDirect(sky)), sky, options);
  ASSERT_TRUE(lit) << lit.message();
  const MeshLighting& lighting = *lit;
  EXPECT_EQ(lighting.unusable_normals, 0u);
  const std::vector<glm::dvec3> sphere_truth = GroundTruthIrradiance(sky, SphereNormals(500), 1);
  glm::dvec3 sky_mean(0.0), mesh_mean(0.0);
  for (const glm::dvec3& e : sphere_truth) sky_mean += e / static_cast<double>(sphere_truth.size());
  for (const glm::dvec3& e : lighting.irradiance) mesh_mean += e / static_cast<double>(lighting.irradiance.size());
  // A sane range, not a fit: the mesh's normals are not spread evenly over the sphere.
  for (int c = 0; c < 3; ++c) {
    EXPECT_GT(mesh_mean[c], 0.5 * sky_mean[c]) << "channel " << c;
    EXPECT_LT(mesh_mean[c], 2.0 * sky_mean[c]) << "channel " << c;
  }
}

// Two triangles with one zero normal in the file: that vertex gets a computed normal, the other
// three keep the file's bits (what the loader gives without the repair).
TEST(LoadMeshGeometry, OnlyUnusableNormalsAreReplaced) {
  const std::filesystem::path file = std::filesystem::path(::testing::TempDir()) / "vs11_one_zero_normal.obj";
  std::ofstream(file) << "v 0 0 0\nv 1 0 0\nv 1 1 0.5\nv 0 1 0\n"
                         "vn 0.6 0 0.8\nvn 0 0 0\nvn 0 0.28 0.96\n"
                         "f 1//1 2//2 3//3\nf 1//1 3//3 4//1\n";
  MeshGeometry geometry;
  std::vector<std::string> warnings;
  ASSERT_EQ(LoadMeshGeometry(file.string(), geometry, warnings).message(), "");
  const Result<mesh::Mesh> plain = mesh::LoadMesh(file);
  ASSERT_TRUE(plain.ok()) << plain.message();
  ASSERT_EQ(geometry.normals.size(), plain->vertex_count);
  int replaced = 0;
  for (std::size_t i = 0; i < geometry.normals.size(); ++i) {
    const Vec4f& from_file = plain->normals[i];
    ASSERT_NEAR(glm::length(glm::dvec3(geometry.normals[i])), 1.0, kUnitTolerance) << "vertex " << i;
    if (from_file[0] == 0 && from_file[1] == 0 && from_file[2] == 0) {
      ++replaced;
      continue;
    }
    EXPECT_EQ(std::memcmp(&geometry.normals[i][0], &from_file[0], 3 * sizeof(float)), 0) << "vertex " << i;
  }
  EXPECT_EQ(replaced, 1);
  EXPECT_THAT(AllWarnings(warnings), HasSubstr(": 1 of 6 vertices have no usable normal"));
  std::filesystem::remove(file);
}

TEST(LoadMeshGeometry, GoodNormalsKeepTheirBitsAndGiveNoWarning) {
  MeshGeometry geometry;
  std::vector<std::string> warnings;
  ASSERT_EQ(LoadMeshGeometry(kWusonPly, geometry, warnings).message(), "");
  const Result<mesh::Mesh> plain = mesh::LoadMesh(kWusonPly);
  ASSERT_TRUE(plain.ok()) << plain.message();
  ASSERT_EQ(geometry.normals.size(), plain->vertex_count);
  for (std::size_t i = 0; i < geometry.normals.size(); ++i) {
    ASSERT_EQ(std::memcmp(&geometry.normals[i][0], &plain->normals[i][0], 3 * sizeof(float)), 0) << "vertex " << i;
  }
  EXPECT_THAT(AllWarnings(warnings), ::testing::Not(HasSubstr("computed")));
}

// --compute-normals: every normal computed, the file's usable ones too.
TEST(LoadMeshGeometry, ComputeNormalsReplacesGoodNormals) {
  MeshGeometry file_normals, computed;
  std::vector<std::string> warnings;
  ASSERT_EQ(LoadMeshGeometry(kWusonPly, file_normals, warnings).message(), "");
  ASSERT_EQ(LoadMeshGeometry(kWusonPly, computed, warnings, 0, /*compute_normals=*/true).message(), "");
  ASSERT_EQ(computed.normals.size(), file_normals.normals.size());
  std::size_t differ = 0;
  for (std::size_t i = 0; i < computed.normals.size(); ++i) {
    ASSERT_NEAR(glm::length(glm::dvec3(computed.normals[i])), 1.0, kUnitTolerance) << "vertex " << i;
    if (computed.normals[i] != file_normals.normals[i]) ++differ;
  }
  EXPECT_GT(differ, computed.normals.size() / 2);
}

}  // namespace
}  // namespace vs11::irradiance
