#include "irradiance/jobs/irrmap_job.h"

#include <algorithm>
#include <string_view>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "irradiance/io/environment_io.h"
#include "irradiance/io/environments.h"
#include "irradiance/sh/latlong_projection.h"
#include "irradiance/sh/sh_projection.h"
#include "vm/io/vertex_io.h"
#include "vm/reference/program_references.h"

namespace vs11::irradiance {
namespace {

namespace fs = std::filesystem;
using testing::HasSubstr;

// The program in float against eq. (6) in double (see constants_output_test.cc).
constexpr double kProgramRelativeTolerance = 1e-5;
// Levels of at least 16 x 16 keep the error of full resolution (the paper's Fig. 3): measured on
// the 128 x 128 sky, the max relative error moves by < 0.4% and the mean by < 0.01% (absolute, in
// units of relative error); these limits leave room.
constexpr double kCoarseLevelMaxErrorChange = 0.01;
constexpr double kCoarseLevelMeanErrorChange = 0.002;
// SH9 of a constant environment is exact, at every level (the box filter keeps a constant). What is
// left is the ground truth's own quadrature error: at face size 32 the kink of max(0, n . l) at the
// horizon cuts through texels, measured 1.4e-4 relative.
constexpr double kFurnaceError = 5e-4;

// A fresh folder under the test temp dir, removed afterwards.
class IrrmapJob : public testing::Test {
 protected:
  void SetUp() override {
    folder_ = fs::path(testing::TempDir()) /
              fmt::format("irrmap_job_test_{}_{}", testing::UnitTest::GetInstance()->current_test_info()->name(),
                          std::random_device{}());
    fs::remove_all(folder_);
    fs::create_directories(folder_);
    options_.face_size = 32;
    options_.out_dir = folder_ / "out";
    options_.error_normals = 300;
    options_.sphere_diameter = 32;
    options_.map_size = 16;
    options_.threads = 2;
  }
  void TearDown() override { fs::remove_all(folder_); }

  // No output file at all: the out folder does not exist or is empty.
  void ExpectNoOutput() const {
    if (fs::exists(options_.out_dir)) {
      EXPECT_TRUE(fs::is_empty(options_.out_dir));
    }
  }

  fs::path folder_;
  IrrmapOptions options_;
  IrrmapReport report_;
};

std::string ReadText(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(Irrmap, DefaultLevelIsThe64x64LevelOfLargerFaces) {
  EXPECT_EQ(DefaultLevel(1), 0);
  EXPECT_EQ(DefaultLevel(32), 0);
  EXPECT_EQ(DefaultLevel(64), 0);
  EXPECT_EQ(DefaultLevel(128), 1);
  EXPECT_EQ(DefaultLevel(256), 2);
  EXPECT_EQ(DefaultLevel(2048), 5);
}

TEST(Irrmap, PaperProgramReadsItsRegistersFromTheMetadataAndMatchesEq6) {
  Result<PaperProgram> program = PaperProgram::Load();
  ASSERT_TRUE(program) << program.message();
  EXPECT_EQ(program->normal_register(), 0);
  EXPECT_EQ(program->constant_base(), 0);
  EXPECT_EQ(OutputSlotName(program->output_slot()), "oD0");
  const Sh9Rgb sh = RandomCoefficients(3);
  const std::vector<glm::dvec3> normals = SphereNormals(400);
  for (std::string kind : {"ref", "batch"}) {
    const Result<std::vector<glm::dvec3>> evaluated = program->Irradiance(PackTable1(sh), normals, kind);
    ASSERT_TRUE(evaluated) << evaluated.message();
    const std::vector<glm::dvec3>& actual = *evaluated;
    ASSERT_EQ(actual.size(), normals.size());
    double scale = 0.0;
    for (const glm::dvec3& n : normals) scale = std::max(scale, glm::length(IrradianceEq6(sh, n)));
    for (std::size_t i = 0; i < normals.size(); ++i) {
      const glm::dvec3 expected = IrradianceEq6(sh, normals[i]);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(actual[i][c], expected[c], kProgramRelativeTolerance * scale);
    }
  }
}

TEST_F(IrrmapJob, WritesTheFiveFilesForASmallBuiltin) {
  options_.environment = "sky";
  ASSERT_EQ(RunIrrmap(options_, report_).message(), "");
  const fs::path out = options_.out_dir;
  for (const char* name : {"coeffs.json", "constants.vsh", "program.vsh", "irradiance.exr", "preview.png"}) {
    EXPECT_TRUE(fs::is_regular_file(out / name)) << name;
  }
  EXPECT_EQ(report_.files.size(), 5u);
  // Nothing else (no temporaries).
  EXPECT_EQ(std::distance(fs::directory_iterator(out), fs::directory_iterator()), 5);

  // coeffs.json: the documented keys, and the coefficients of the chosen level.
  const nlohmann::json json = nlohmann::json::parse(ReadText(out / "coeffs.json"));
  for (const char* key : {"coefficients", "level", "face_size", "layout", "timings_ms", "constants", "levels"}) {
    EXPECT_TRUE(json.contains(key)) << key;
  }
  for (const char* key : {"load", "env_mips", "basis_pyramid", "projection", "constants", "irradiance_map",
                          "ground_truth"}) {
    EXPECT_TRUE(json["timings_ms"].contains(key)) << key;
  }
  EXPECT_EQ(json["level"], 0);
  EXPECT_EQ(json["face_size"], 32);
  EXPECT_EQ(json["layout"], "builtin");
  EXPECT_EQ(json["levels"].size(), 6u);
  const Result<Sh9Rgb> parsed = ParseCoefficientsJson(ReadText(out / "coeffs.json"));
  ASSERT_TRUE(parsed) << parsed.message();
  const CubeMap sky = *MakeBuiltinEnvironment("sky", 32);
  const Sh9Rgb direct = ProjectDirect(sky);
  for (int i = 0; i < kSh9Coefficients; ++i) {
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(parsed->coefficients[i][c], direct.coefficients[i][c], 1e-5) << "coefficient " << i;
    }
  }

  // constants.vsh: the packed registers, bit for bit, at c0..c6.
  ConstantBank bank;
  Diagnostics diagnostics;
  ParseConstantsText(ReadText(out / "constants.vsh"), "constants.vsh", bank, diagnostics);
  ASSERT_FALSE(diagnostics.HasErrors()) << diagnostics.ToString();
  for (int i = 0; i < 7; ++i) {
    for (int c = 0; c < 4; ++c) EXPECT_EQ(bank[i][c], report_.constants.registers[i][c]);
  }
  EXPECT_THAT(ReadText(out / "constants.vsh"), HasSubstr("cAr"));

  // irradiance.exr: a horizontal cross of map_size faces whose +y centre is the program's value.
  auto exr = OIIO::ImageInput::open((out / "irradiance.exr").string());
  ASSERT_TRUE(exr);
  EXPECT_EQ(exr->spec().width, 4 * options_.map_size);
  EXPECT_EQ(exr->spec().height, 3 * options_.map_size);
  EXPECT_EQ(exr->spec().format, OIIO::TypeDesc::FLOAT);
  exr->close();
  Result<LoadedEnvironment> cross = LoadEnvironment(out / "irradiance.exr");
  ASSERT_TRUE(cross.ok()) << cross.message();
  const int m = options_.map_size;
  const glm::dvec3 up = TexelDirection(CubeFace::kPositiveY, m / 2, m / 2, m);
  const glm::dvec3 expected = IrradianceEq6(report_.coefficients, up);
  const glm::vec3 texel = cross->cube.face(CubeFace::kPositiveY).at(m / 2, m / 2);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(texel[c], expected[c], kProgramRelativeTolerance * glm::length(expected));

  // preview.png: 8-bit, with spheres drawn.
  auto png = OIIO::ImageInput::open((out / "preview.png").string());
  ASSERT_TRUE(png);
  EXPECT_GT(png->spec().width, 2 * options_.sphere_diameter);
  EXPECT_GT(png->spec().height, options_.sphere_diameter);
  png->close();
}

TEST_F(IrrmapJob, CoefficientsOnlyWritesTheSameCoefficientsAndNoMore) {
  options_.environment = "studio";
  options_.level = 2;
  ASSERT_EQ(RunIrrmap(options_, report_).message(), "");
  const Sh9Rgb full_run = report_.coefficients;
  options_.out_dir = folder_ / "coefficients_only";
  options_.coefficients_only = true;
  ASSERT_EQ(RunIrrmap(options_, report_).message(), "");
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(options_.out_dir)) names.push_back(entry.path().filename());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"coeffs.json", "constants.vsh", "program.vsh"}));
  EXPECT_EQ(report_.TimingMs("ground_truth"), 0.0);
  const nlohmann::json json = nlohmann::json::parse(ReadText(options_.out_dir / "coeffs.json"));
  EXPECT_FALSE(json["levels"][0].contains("mean_relative_error"));
  const Result<Sh9Rgb> parsed = ParseCoefficientsJson(ReadText(options_.out_dir / "coeffs.json"));
  ASSERT_TRUE(parsed) << parsed.message();
  for (int i = 0; i < kSh9Coefficients; ++i) EXPECT_EQ(parsed->coefficients[i], full_run.coefficients[i]) << i;
}

TEST_F(IrrmapJob, ReportsEveryLevelAndCoarseLevelsKeepTheFullResolutionError) {
  options_.environment = "sky";
  options_.face_size = 128;
  options_.level = 3;
  ASSERT_EQ(RunIrrmap(options_, report_).message(), "");
  EXPECT_EQ(report_.level, 3);
  ASSERT_EQ(report_.levels.size(), 8u);
  const ErrorStats& full = report_.levels[0].error;
  for (const LevelReport& level : report_.levels) {
    EXPECT_EQ(level.size, 128 >> level.level);
    EXPECT_EQ(level.chosen, level.level == 3);
    EXPECT_GT(level.update_ms, 0.0);
    if (level.size >= 16) {
      EXPECT_NEAR(level.error.max_relative, full.max_relative, kCoarseLevelMaxErrorChange) << level.level;
      EXPECT_NEAR(level.error.mean_relative, full.mean_relative, kCoarseLevelMeanErrorChange) << level.level;
    }
  }
  // The 1 x 1 level keeps only the mean radiance of each face: far worse.
  EXPECT_GT(report_.levels.back().error.mean_relative, 2.0 * full.mean_relative);
  const std::string table = FormatLevelTable(report_);
  EXPECT_THAT(table, HasSubstr("*     3"));
  EXPECT_THAT(table, HasSubstr("128x128"));
  EXPECT_GT(report_.TimingMs("ground_truth"), 0.0);
}

TEST_F(IrrmapJob, WhiteFurnaceHasNoErrorAtAnyLevel) {
  options_.environment = "constant";
  ASSERT_EQ(RunIrrmap(options_, report_).message(), "");
  for (const LevelReport& level : report_.levels) {
    EXPECT_LT(level.error.max_relative, kFurnaceError) << "level " << level.level;
  }
}

TEST_F(IrrmapJob, RejectsAnOutOfRangeLevelNamingTheRange) {
  options_.environment = "sky";
  options_.level = 6;
  const Status error = RunIrrmap(options_, report_);
  ASSERT_FALSE(error.ok());
  EXPECT_THAT(error.message(), HasSubstr("--level 6"));
  EXPECT_THAT(error.message(), HasSubstr("0 (32x32) to 5 (1x1)"));
  ExpectNoOutput();
  options_.level = -1;
  EXPECT_FALSE(RunIrrmap(options_, report_).ok());
  ExpectNoOutput();
}

TEST_F(IrrmapJob, RejectsAMissingFile) {
  options_.environment = (folder_ / "missing.exr").string();
  const Status error = RunIrrmap(options_, report_);
  ASSERT_FALSE(error.ok());
  EXPECT_EQ(error.error().code, DiagnosticCode::kNoSuchInput);
  EXPECT_THAT(error.message(), HasSubstr("missing.exr"));
  ExpectNoOutput();
}

TEST_F(IrrmapJob, RejectsALayoutThatDoesNotFitTheFile) {
  const fs::path cross = folder_ / "cross.exr";
  ASSERT_EQ(WriteCrossExr(*MakeBuiltinEnvironment("spot", 16), cross).message(), "");
  options_.environment = cross.string();
  options_.layout = EnvironmentLayout::kLatLong;
  EXPECT_FALSE(RunIrrmap(options_, report_).ok());
  ExpectNoOutput();
}

TEST_F(IrrmapJob, RejectsACubeWhoseFaceSizeIsNotAPowerOfTwo) {
  const fs::path cross = folder_ / "cross24.exr";
  ASSERT_EQ(WriteCrossExr(MakeConstant(24), cross).message(), "");
  options_.environment = cross.string();
  const Status error = RunIrrmap(options_, report_);
  ASSERT_FALSE(error.ok());
  EXPECT_THAT(error.message(), HasSubstr("power of two"));
  ExpectNoOutput();
}

TEST_F(IrrmapJob, RejectsBadOptionsBeforeAnyWork) {
  options_.environment = "nosuchbuiltin";
  EXPECT_THAT(RunIrrmap(options_, report_).message(), HasSubstr("built-in"));
  options_.environment = "sky";
  options_.engine = "gpu";
  EXPECT_THAT(RunIrrmap(options_, report_).message(), HasSubstr("gpu"));
  options_.engine = "ref";
  options_.face_size = 48;
  EXPECT_THAT(RunIrrmap(options_, report_).message(), HasSubstr("power of two"));
  options_.face_size = 32;
  options_.map_size = 0;
  const Status map_size = RunIrrmap(options_, report_);
  EXPECT_THAT(map_size.message(), HasSubstr("--map-size"));
  EXPECT_EQ(map_size.error().code, DiagnosticCode::kOptionValue);
  EXPECT_EQ(CheckIrrmapOptions(options_).message(), map_size.message()) << "the same check, before any work";
  ExpectNoOutput();
}

TEST_F(IrrmapJob, ReadsACrossFileAndNamesItsLayout) {
  const fs::path cross = folder_ / "studio.exr";
  ASSERT_EQ(WriteCrossExr(*MakeBuiltinEnvironment("studio", 16), cross).message(), "");
  options_.environment = cross.string();
  options_.engine = "ref";
  ASSERT_EQ(RunIrrmap(options_, report_).message(), "");
  EXPECT_EQ(report_.layout, "hcross");
  EXPECT_EQ(report_.face_size, 16);
  const nlohmann::json json = nlohmann::json::parse(ReadText(options_.out_dir / "coeffs.json"));
  EXPECT_EQ(json["layout"], "hcross");
  EXPECT_EQ(json["engine"], "ref");
}

TEST_F(IrrmapJob, AnUnwritableOutputLeavesNoFiles) {
  // The output "directory" is a file: nothing can be written, and the file stays as it was.
  const fs::path blocker = folder_ / "blocker";
  std::ofstream(blocker) << "x";
  options_.environment = "spot";
  options_.out_dir = blocker / "out";
  const Status error = RunIrrmap(options_, report_);
  ASSERT_FALSE(error.ok());
  EXPECT_THAT(error.message(), HasSubstr("blocker"));
  EXPECT_EQ(ReadText(blocker), "x");
  EXPECT_EQ(std::distance(fs::directory_iterator(folder_), fs::directory_iterator()), 1);
}

TEST_F(IrrmapJob, AFolderInPlaceOfAnOutputFailsBeforeAnythingIsReplaced) {
  options_.environment = "spot";
  fs::create_directories(options_.out_dir / "preview.png");
  std::ofstream(options_.out_dir / "coeffs.json") << "old";
  const Status error = RunIrrmap(options_, report_);
  ASSERT_FALSE(error.ok());
  EXPECT_THAT(error.message(), HasSubstr("preview.png"));
  EXPECT_EQ(ReadText(options_.out_dir / "coeffs.json"), "old");
  EXPECT_EQ(std::distance(fs::directory_iterator(options_.out_dir), fs::directory_iterator()), 2);
}

// ---- lat-long maps: projected where they lie, resampled to a cube only for the stages that read one

// A 256 x 128 panorama: a gradient and a small bright patch.
Image Panorama() {
  Image image(256, 128);
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const bool patch = x >= 90 && x < 96 && y >= 30 && y < 34;
      image.at(x, y) = glm::vec3(0.2f + 0.005f * static_cast<float>(y), 0.5f, patch ? 400.0f : 0.1f);
    }
  }
  return image;
}

// Writes Panorama() to a float EXR in `folder` and makes it the job's environment (no window).
bool UsePanoramaFile(const fs::path& folder, IrrmapOptions& options) {
  const fs::path file = folder / "pano.exr";
  options.environment = file.string();
  options.window = ShWindow::kNone;
  return WriteImage(Panorama(), file).ok();
}

bool HasTiming(const IrrmapReport& report, std::string_view name) {
  return std::any_of(report.timings.begin(), report.timings.end(),
                     [&](const Timing& timing) { return timing.name == name; });
}

double LargestDifference(const Sh9Rgb& a, const Sh9Rgb& b) {
  double worst = 0.0, largest = 0.0;
  for (int i = 0; i < kSh9Coefficients; ++i) {
    for (int c = 0; c < 3; ++c) {
      worst = std::max(worst, std::abs(a.coefficients[i][c] - b.coefficients[i][c]));
      largest = std::max(largest, std::abs(b.coefficients[i][c]));
    }
  }
  return worst / largest;
}

TEST_F(IrrmapJob, LatLongCoefficientsOnlyProjectThePanoramaInPlaceAndBuildNoCube) {
  ASSERT_TRUE(UsePanoramaFile(folder_, options_));
  options_.coefficients_only = true;
  options_.no_ground_truth = true;
  options_.level = 0;
  ASSERT_EQ(RunIrrmap(options_, report_).message(), "");
  EXPECT_TRUE(HasTiming(report_, "latlong_pyramid"));
  EXPECT_FALSE(HasTiming(report_, "resample_cube"));
  EXPECT_FALSE(HasTiming(report_, "env_mips"));
  EXPECT_EQ(report_.layout, "latlong");
  EXPECT_EQ(report_.face_size, 32);
  ASSERT_EQ(report_.levels.size(), 6u);
  for (int k = 0; k < 6; ++k) EXPECT_EQ(report_.levels[static_cast<std::size_t>(k)].size, 32 >> k);
  // Level 0 is the panorama's own exact projection, which the cube route approximates.
  EXPECT_LT(LargestDifference(report_.coefficients, ProjectLatLong(Panorama())), 1e-12);
  EXPECT_LT(LargestDifference(report_.coefficients, ProjectDirect(ResampleLatLong(Panorama(), 32))), 2e-3);
}

TEST_F(IrrmapJob, LatLongTheIrradianceMapNeedsNoCubeButTheGroundTruthResamplesOnce) {
  ASSERT_TRUE(UsePanoramaFile(folder_, options_));
  options_.no_ground_truth = true;
  ASSERT_EQ(RunIrrmap(options_, report_).message(), "");
  EXPECT_FALSE(HasTiming(report_, "resample_cube"));
  EXPECT_EQ(report_.irradiance_map.face_size, 16);
  options_.no_ground_truth = false;
  ASSERT_EQ(RunIrrmap(options_, report_).message(), "");
  EXPECT_EQ(std::count_if(report_.timings.begin(), report_.timings.end(),
                          [](const Timing& timing) { return timing.name == "resample_cube"; }),
            1);
  EXPECT_TRUE(report_.errors_measured);
  // The nine terms of a smooth panorama against the exact convolution of its cube.
  EXPECT_LT(report_.levels[0].error.max_peak, 0.2);
}

TEST_F(IrrmapJob, LatLongAnArrayInMemoryGivesWhatItsFileGives) {
  ASSERT_TRUE(UsePanoramaFile(folder_, options_));
  options_.coefficients_only = true;
  ASSERT_EQ(RunIrrmap(options_, report_).message(), "");
  const Sh9Rgb from_file = report_.coefficients;
  const int level = report_.level;
  options_.latlong = Panorama();
  options_.environment = "array";
  options_.layout = EnvironmentLayout::kLatLong;
  ASSERT_EQ(RunIrrmap(options_, report_).message(), "");
  EXPECT_EQ(report_.level, level);
  EXPECT_EQ(LargestDifference(report_.coefficients, from_file), 0.0);
}

}  // namespace
}  // namespace vs11::irradiance
