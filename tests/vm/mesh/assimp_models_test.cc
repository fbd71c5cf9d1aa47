// Every file of Debian's assimp-testmodels that Assimp has an importer for, through `vs11 run
// --mesh` with programs/directional_light.vsh (dcl_position, dcl_normal). A model that loads with
// normals must run and write one oD0 row per vertex; one without normals must be refused with the
// --compute-normals hint; one that does not load must be refused with an error naming it. Nothing
// may crash or hang (the process exits 0 or 1). Models with normals but only points or lines run
// here and are refused by irrmap --mesh (tests/irradiance/jobs/mesh_lighting_test.cc says which).
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/run_tool.h"
#include "tests/vm/mesh/mesh_test_support.h"
#include "vm/mesh/mesh_io.h"
#include "vm/mesh/npy.h"

namespace vs11::mesh {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> ModelFiles() {
  std::vector<std::string> files;
  std::error_code error;
  for (auto it = fs::recursive_directory_iterator(vs11::testing::kAssimpModels, error);
       !error && it != fs::recursive_directory_iterator(); it.increment(error)) {
    if (it->is_regular_file() && IsMeshFileExtension(it->path().extension().string())) files.push_back(it->path().string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

class AssimpModel : public ::testing::TestWithParam<std::string> {};

TEST(AssimpModels, ThePackageIsInstalled) {
  // assimp-testmodels 5.2.5 holds 414 files with an extension Assimp reads.
  EXPECT_GE(ModelFiles().size(), 400u) << "install assimp-testmodels (bash .ci/setup does)";
}

// Every model is loaded in-process; VS11_MODEL_RUN_STRIDE=N (set by .ci/sanitize, where each tool
// start under ASan costs about a second) runs the tool on every Nth model only.
std::size_t ToolRunStride() {
  const char* text = std::getenv("VS11_MODEL_RUN_STRIDE");
  const long stride = text == nullptr ? 1 : std::strtol(text, nullptr, 10);
  return stride < 1 ? 1 : static_cast<std::size_t>(stride);
}

TEST_P(AssimpModel, RunsOrIsRefusedClearly) {
  const std::string file = GetParam();
  const Result<Mesh> loaded = LoadMesh(file);
  static const std::vector<std::string> files = ModelFiles();
  const std::size_t index = static_cast<std::size_t>(std::find(files.begin(), files.end(), file) - files.begin());
  if (index % ToolRunStride() != 0) return;
  const fs::path out = fs::path(::testing::TempDir()) / ("vs11_assimp_model_" + std::to_string(index));
  fs::remove_all(out);
  const auto result = vs11::testing::RunVs11("run " + std::string(VS11_SOURCE_DIR) + "/programs/directional_light.vsh --missing zeros --mesh '" +
                                             file + "' --out-npy " + out.string());
  ASSERT_TRUE(result.status == 0 || result.status == 1) << "status " << result.status << "\n" << result.output;
  if (!loaded.ok()) {
    EXPECT_EQ(result.status, 1);
    EXPECT_NE(result.output.find("error: " + file), std::string::npos) << result.output;
  } else if (loaded->normals.empty()) {
    EXPECT_EQ(result.status, 1);
    EXPECT_NE(result.output.find("--compute-normals"), std::string::npos) << result.output;
  } else {
    ASSERT_EQ(result.status, 0) << result.output;
    const Result<NpyArray> od0 = ReadNpy(out / "oD0.npy");
    ASSERT_TRUE(od0.ok()) << od0.message();
    EXPECT_EQ(od0->rows, loaded->vertex_count);
  }
  fs::remove_all(out);
}

std::string TestName(const ::testing::TestParamInfo<std::string>& info) {
  std::string name = fs::path(info.param).lexically_relative(vs11::testing::kAssimpModels).string();
  for (char& c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  }
  return name + "_" + std::to_string(info.index);
}

INSTANTIATE_TEST_SUITE_P(All, AssimpModel, ::testing::ValuesIn(ModelFiles()), TestName);
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(AssimpModel);

}  // namespace
}  // namespace vs11::mesh
