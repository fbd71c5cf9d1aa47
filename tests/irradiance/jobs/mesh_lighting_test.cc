// irrmap --mesh: every Assimp test model with triangles lit by the paper's program, and the tool end to end.
#include "irradiance/jobs/mesh_lighting.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "irradiance/io/environment_io.h"
#include "irradiance/jobs/irrmap_job.h"
#include "irradiance/mesh_input/mesh_geometry_io.h"
#include "irradiance/render/preview.h"
#include "irradiance/sh/sh_projection.h"
#include "tests/run_tool.h"
#include "vm/mesh/mesh_io.h"

namespace vs11::irradiance {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

constexpr const char* kModels = "/usr/share/assimp/models";
constexpr const char* kWuson = "/usr/share/assimp/models/PLY/Wuson.ply";
// Above this many vertices a model runs without the exact irradiance (it would dominate the test).
constexpr std::size_t kTestTruthLimit = 20000;
constexpr int kTestFaceSize = 8;

// A constant environment's irradiance is pi L for every unit normal, and nine SH coefficients hold
// it exactly, so the program's only error against the brute-force truth is the truth's own
// discretisation over the cube's texels: measured here, for the tolerance.
double ConstantTruthError(int face_size) {
  CubeMap environment(face_size, glm::vec3(1.0f));
  const std::vector<glm::dvec3> normals = SphereNormals(500);
  double worst = 0.0;
  for (const glm::dvec3& e : GroundTruthIrradiance(environment, normals, 1)) {
    worst = std::max(worst, std::abs(e.g - M_PI) / M_PI);
  }
  return worst;
}


using MeshLightingTest = vs11::testing::ToolFolderTest;

// The files are those tests/vm/mesh/assimp_models_test.cc runs through `vs11 run --mesh`: every file
// whose extension Assimp reads (IsMeshFileExtension, which includes the .xml of Ogre, Collada and
// XGL models). Of those that load with normals, vs11 run runs them all, while irrmap refuses the
// ones without triangles (assimp-testmodels 5.2.5: PLY/points.ply, PLY/pond.0.ply,
// PLY/issue623.ply and OBJ/point_cloud.obj, points only): a vertex shader needs no triangles, a
// lit picture does. irrmap also lights the models whose normals are missing or zero, with computed
// ones (LoadMeshGeometry): 319 lit with 5.2.5, of which 239 have normals in the file (about 10 s of
// this test's 34 s are the 80 with computed normals).
TEST_F(MeshLightingTest, EveryTestModelWithTrianglesIsLitAsIrrmapDoes) {
  ASSERT_TRUE(fs::is_directory(kModels)) << "assimp-testmodels is not installed (.ci/setup installs it)";
  int lit = 0, without_normals = 0, without_triangles = 0, unreadable = 0, with_truth = 0;
  // Float rounding of the program, and the sphere sample missing the worst normal by a little.
  const double tolerance = 1.5 * ConstantTruthError(kTestFaceSize) + 1e-5;
  for (const auto& entry : fs::recursive_directory_iterator(kModels)) {
    if (!entry.is_regular_file() || !mesh::IsMeshFileExtension(entry.path().extension().string())) continue;
    MeshGeometry geometry;
    std::vector<std::string> warnings;
    Status error = LoadMeshGeometry(entry.path().string(), geometry, warnings);
    if (!error.ok()) {
      if (error.message().find("no normals") != std::string::npos) {
        ++without_normals;
      } else if (error.message().find("no triangles") != std::string::npos) {
        ++without_triangles;
      } else {
        ++unreadable;
      }
      continue;
    }
    SCOPED_TRACE(entry.path().string());
    IrrmapOptions options;
    options.environment = "constant";
    options.face_size = kTestFaceSize;
    options.coefficients_only = true;
    options.threads = 2;
    options.out_dir = dir_ / "out";
    options.mesh = std::move(geometry);
    options.mesh_truth_vertex_limit = kTestTruthLimit;
    // The picture's pixels (tone mapping, PNG encoding) were most of this sweep's time; the
    // picture's content is checked by the Wuson tests below.
    options.mesh_panel_size = 48;
    IrrmapReport report;
    ASSERT_EQ(RunIrrmap(options, report).message(), "");
    ASSERT_TRUE(report.mesh);
    EXPECT_EQ(report.mesh->vertex_count, options.mesh->positions.size());
    EXPECT_TRUE(fs::exists(dir_ / "out" / "mesh.ply"));
    EXPECT_TRUE(fs::exists(dir_ / "out" / "mesh.png"));
    EXPECT_GT(report.mesh->ms_per_evaluation, 0.0);
    if (report.mesh->has_truth) {
      ++with_truth;
      EXPECT_LT(report.mesh->error.max_relative, tolerance);
    }
    ++lit;
  }
  std::printf("[ models ] %d lit (%d with the exact irradiance), %d without normals, %d without triangles, %d not read\n",
              lit, with_truth, without_normals, without_triangles, unreadable);
  EXPECT_GT(lit, 50);
}

TEST_F(MeshLightingTest, PictureShowsTheLitMeshBesideTheTruthAndTheError) {
  MeshGeometry geometry;
  std::vector<std::string> warnings;
  ASSERT_EQ(LoadMeshGeometry(kWuson, geometry, warnings).message(), "");
  Result<PaperProgram> program = PaperProgram::Load();
  ASSERT_TRUE(program) << program.message();
  // A constant environment of radiance 1: E = pi for every normal.
  CubeMap environment(kTestFaceSize, glm::vec3(1.0f));
  const double truth_error = ConstantTruthError(kTestFaceSize);
  SevenConstants constants = PackTable1(ProjectDirect(environment));
  MeshLightingOptions options;
  options.panel_size = 96;
  Result<MeshLighting> lit = LightMesh(geometry, *program, constants, environment, options);
  ASSERT_TRUE(lit) << lit.message();
  MeshLighting& lighting = *lit;
  ASSERT_EQ(lighting.truth.size(), geometry.positions.size());
  EXPECT_NEAR(lighting.irradiance[0].g, M_PI, 1e-5);
  EXPECT_NEAR(lighting.truth[0].g, M_PI, 1.5 * M_PI * truth_error);
  EXPECT_EQ(lighting.picture.width, 3 * 96 + 2 * 8);
  EXPECT_EQ(lighting.picture.height, 96);
  // Uniform light: every covered pixel of the first two panels shows nearly the same grey, the
  // brightest (exposure from the brightest of program and truth, which differ by truth_error).
  const double shade = 3 * truth_error * kSphereWhite;
  EXPECT_NEAR(lighting.picture.at(48, 48).r, kSphereWhite, shade);
  EXPECT_NEAR(lighting.picture.at(96 + 8 + 48, 48).r, kSphereWhite, shade);
  EXPECT_NE(lighting.picture.at(0, 0), lighting.picture.at(48, 48));  // background in the corner
  EXPECT_NEAR(lighting.display_colors[0][0], LinearToSrgb(lighting.exposure * lighting.irradiance[0].r), 1e-6);
}

TEST_F(MeshLightingTest, IrrmapWritesMeshFilesAndStatistics) {
  const fs::path out = dir_ / "out";
  vs11::testing::CommandResult run = vs11::testing::RunIrrmap(
      fmt::format("sky --face-size 16 --map-size 4 --error-normals 20 --sphere-size 16 --mesh {} --out '{}'", kWuson,
                  out.string()));
  ASSERT_EQ(run.status, 0) << run.output;
  std::ifstream in(out / "coeffs.json");
  nlohmann::json coeffs = nlohmann::json::parse(in);
  const nlohmann::json& mesh = coeffs["mesh"];
  EXPECT_EQ(mesh["vertex_count"], 11184);
  EXPECT_EQ(mesh["triangle_count"], 3732);
  EXPECT_TRUE(mesh["exact"].get<bool>());
  EXPECT_GT(mesh["ms_per_evaluation"].get<double>(), 0.0);
  EXPECT_GT(mesh["max_relative_error"].get<double>(), mesh["mean_relative_error"].get<double>());
  EXPECT_LT(mesh["mean_relative_error"].get<double>(), 0.5);
  Result<mesh::Mesh> ply = mesh::LoadMesh(out / "mesh.ply");
  ASSERT_TRUE(ply.ok()) << ply.message();
  EXPECT_EQ(ply->vertex_count, 11184u);
  ASSERT_NE(ply->Find(mesh::Attribute::kColor), nullptr);
  EXPECT_TRUE(fs::exists(out / "mesh.png"));
}

TEST_F(MeshLightingTest, IrrmapLightsAMeshWithoutNormalsAndSaysSo) {
  const fs::path model = dir_ / "flat.obj";
  std::ofstream(model) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  const fs::path out = dir_ / "out";
  vs11::testing::CommandResult run = vs11::testing::RunIrrmap(fmt::format(
      "sky --face-size 16 --map-size 4 --error-normals 20 --sphere-size 16 --mesh '{}' --out '{}'", model.string(),
      out.string()));
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_THAT(run.output, HasSubstr("irrmap: warning: " + model.string() +
                                    ": 3 of 3 vertices have no usable normal (none, zero or not finite) in the file: "
                                    "computed smooth normals for them"));
  std::ifstream in(out / "coeffs.json");
  nlohmann::json coeffs = nlohmann::json::parse(in);
  EXPECT_EQ(coeffs["mesh"]["unusable_normals"], 0);
  EXPECT_TRUE(fs::exists(out / "mesh.png"));
}

}  // namespace
}  // namespace vs11::irradiance
