// irrmap's outputs for engines: --map-format (the irradiance cube as DDS, KTX2, KTX or six .hdr faces) and --sh-export
// (the coefficients in engines' conventions), through RunIrrmap.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "irradiance/io/dds_reader.h"
#include "irradiance/io/environment_io.h"
#include "irradiance/jobs/irrmap_job.h"
#include "irradiance/sh/engine_sh.h"
#include "tests/irradiance/io/environment_test_support.h"

namespace vs11::irradiance {
namespace {

namespace fs = std::filesystem;
using testing::HasSubstr;

// Half floats keep 11 significant bits: a relative rounding error of at most 2^-11.
constexpr float kHalfRelativeError = 1.0f / 2048.0f;

class IrrmapExports : public testing::Test {
 protected:
  void SetUp() override {
    folder_ = fs::path(testing::TempDir()) /
              fmt::format("irrmap_exports_test_{}_{}", testing::UnitTest::GetInstance()->current_test_info()->name(),
                          std::random_device{}());
    fs::create_directories(folder_);
    options_.environment = "studio";
    options_.face_size = 16;
    options_.out_dir = folder_ / "out";
    options_.map_size = 8;
    options_.threads = 1;
    options_.no_ground_truth = true;
  }
  void TearDown() override { fs::remove_all(folder_); }

  std::vector<std::string> OutFiles() const {
    std::vector<std::string> names;
    if (!fs::exists(options_.out_dir)) return names;
    for (const auto& entry : fs::directory_iterator(options_.out_dir)) names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }

  fs::path folder_;
  IrrmapOptions options_;
  IrrmapReport report_;
};

TEST_F(IrrmapExports, WritesTheChosenMapFormatAndEachShExportOnce) {
  options_.map_format = MapFileFormat::kKtx2;
  options_.sh_exports = {ShExportFormat::kThree, ShExportFormat::kGlsl, ShExportFormat::kThree};
  ASSERT_EQ(RunIrrmap(options_, report_).message(), "");
  EXPECT_EQ(OutFiles(), (std::vector<std::string>{"coeffs.json", "constants.vsh", "irradiance.ktx2", "program.vsh",
                                                  "sh_irradiance.glsl", "sh_three.json"}));
  EXPECT_EQ(fs::file_size(options_.out_dir / "irradiance.ktx2"), 224u + 6 * 8 * 8 * 8);
  const nlohmann::json three = nlohmann::json::parse(envtest::ReadBytes(options_.out_dir / "sh_three.json"));
  const ShTriples expected = ThreeJsCoefficients(report_.coefficients, AssumedView(ShExportFormat::kThree, ShSourceKind::kCube));
  ASSERT_EQ(three.at("sh").size(), 27u);
  for (int i = 0; i < 9; ++i) {
    for (int c = 0; c < 3; ++c) EXPECT_EQ(three["sh"][3 * i + c].get<double>(), expected[i][c]) << i << ", " << c;
  }
  EXPECT_THAT(three.at("source").get<std::string>(), HasSubstr("studio (built-in), face size 16"));
}

// Read with the DDS reader itself: the environment loader would clamp the studio's few negative
// (ringing) irradiance texels to 0, as it does any radiance.
TEST_F(IrrmapExports, DdsMapReadsBackAsTheIrradianceMap) {
  options_.map_format = MapFileFormat::kDds;
  ASSERT_EQ(RunIrrmap(options_, report_).message(), "");
  EXPECT_FALSE(fs::exists(options_.out_dir / "irradiance.exr"));
  const fs::path file = options_.out_dir / "irradiance.dds";
  const Result<std::optional<DdsFileHeader>> header = ReadDdsHeader(file, 1 << 20);
  ASSERT_TRUE(header.ok() && header->has_value()) << header.message();
  const Result<DdsPixels> pixels = ReadDdsPixels(file, **header);
  ASSERT_TRUE(pixels.ok() && pixels->image.has_value()) << pixels.message();
  const Image& image = *pixels->image;
  const CubeMap& map = report_.irradiance_map;
  ASSERT_EQ(image.height, 6 * map.face_size);
  int negative = 0;
  for (CubeFace face : kAllCubeFaces) {
    for (int y = 0; y < map.face_size; ++y) {
      for (int x = 0; x < map.face_size; ++x) {
        const glm::vec3 expected = map.face(face).at(x, y);
        const glm::vec3 actual = image.at(x, static_cast<int>(face) * map.face_size + y);
        for (int c = 0; c < 3; ++c) {
          negative += expected[c] < 0.0f ? 1 : 0;
          EXPECT_LE(std::abs(actual[c] - expected[c]), kHalfRelativeError * std::abs(expected[c]))
              << CubeFaceName(face) << " (" << x << ", " << y << ") channel " << c;
        }
      }
    }
  }
  EXPECT_GT(negative, 0) << "the studio's map rings below 0 somewhere; those texels keep their sign";
}

// Six files for three.js, each in coeffs.json's "files"; the studio's negative (ringing) texels, which
// RGBE cannot hold, are named in a warning.
TEST_F(IrrmapExports, HdrFacesWritesSixFacesAndWarnsOfNegativeTexels) {
  options_.map_format = MapFileFormat::kHdrFaces;
  ASSERT_EQ(RunIrrmap(options_, report_).message(), "");
  const std::vector<std::string> faces = {"irradiance_nx.hdr", "irradiance_ny.hdr", "irradiance_nz.hdr",
                                          "irradiance_px.hdr", "irradiance_py.hdr", "irradiance_pz.hdr"};
  std::vector<std::string> expected = {"coeffs.json", "constants.vsh"};
  expected.insert(expected.end(), faces.begin(), faces.end());
  expected.push_back("program.vsh");
  EXPECT_EQ(OutFiles(), expected);
  const nlohmann::json coefficients = nlohmann::json::parse(envtest::ReadBytes(options_.out_dir / "coeffs.json"));
  for (const std::string& face : faces) EXPECT_THAT(coefficients.at("files"), testing::Contains(face));
  EXPECT_THAT(report_.warnings, testing::Contains(HasSubstr("are negative (the nine-term irradiance dips below 0)")));
}

TEST_F(IrrmapExports, KtxMapIsOneKtx1CubeFile) {
  options_.map_format = MapFileFormat::kKtx;
  ASSERT_EQ(RunIrrmap(options_, report_).message(), "");
  EXPECT_EQ(OutFiles(), (std::vector<std::string>{"coeffs.json", "constants.vsh", "irradiance.ktx", "program.vsh"}));
  EXPECT_EQ(fs::file_size(options_.out_dir / "irradiance.ktx"), 68u + 6 * 8 * 8 * 8);
}

TEST(IrrmapExportNames, UnknownFormatsListTheNames) {
  EXPECT_EQ(kMapFileFormatNames.UnknownName("png"), "unknown map format 'png' (use exr, dds, ktx2, ktx or hdr-faces)");
  EXPECT_EQ(kShExportFormatNames.UnknownName("unreal"),
            "unknown --sh-export format 'unreal' (use three, filament, unity, gltf, glsl or hlsl)");
}

TEST_F(IrrmapExports, CoefficientsOnlyStillExportsAndSaysTheMapFormatIsUnused) {
  options_.coefficients_only = true;
  options_.map_format = MapFileFormat::kDds;
  options_.sh_exports = {ShExportFormat::kUnity};
  ASSERT_EQ(RunIrrmap(options_, report_).message(), "");
  EXPECT_EQ(OutFiles(), (std::vector<std::string>{"coeffs.json", "constants.vsh", "program.vsh", "sh_unity.json"}));
  EXPECT_THAT(report_.warnings, testing::Contains(HasSubstr("--map-format dds ignored")));
}

}  // namespace
}  // namespace vs11::irradiance
