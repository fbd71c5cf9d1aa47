// Finite environments whose answer overflows float: irrmap, irrmap batch and the in-memory job (the
// Python module's path) give a finite answer where one exists, and otherwise fail the file with a
// message that names the texel range; nothing non-finite reaches a file or a record.
#include "irradiance/jobs/float_range.h"

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "irradiance/jobs/batch_job.h"
#include "irradiance/jobs/irrmap_job.h"
#include "tests/irradiance/io/environment_test_support.h"
#include "tests/run_tool.h"

namespace vs11::irradiance {
namespace {

using namespace envtest;
using ::testing::HasSubstr;
using ::testing::Not;
using FloatRange = TempFolderTest;

constexpr float kFloatMax = std::numeric_limits<float>::max();

Image LatLong(int width, int height, glm::vec3 value) { return Image(width, height, value); }

IrrmapOptions QuickOptions(const fs::path& environment, const fs::path& out) {
  IrrmapOptions options;
  options.environment = environment.string();
  options.face_size = 32;
  options.out_dir = out;
  options.map_size = 4;
  options.error_normals = 20;
  options.sphere_diameter = 16;
  options.threads = 1;
  return options;
}

void ExpectFiniteResults(const IrrmapReport& report) {
  for (const LevelReport& row : report.levels) {
    for (const glm::dvec3& c : row.coefficients.coefficients) {
      ASSERT_TRUE(std::abs(c.r) <= kFloatMax && std::abs(c.g) <= kFloatMax && std::abs(c.b) <= kFloatMax)
          << "level " << row.level;
    }
  }
  for (const glm::vec4& r : report.constants.registers) ASSERT_TRUE(std::isfinite(r.x + r.y + r.z + r.w));
  EXPECT_TRUE(AllTexelsFinite(report.irradiance_map));
}

TEST_F(FloatRange, LatLongOfHugeTexelsFailsWithTheTexelRangeAndWritesNothing) {
  WritePfm(Path("bright.pfm"), LatLong(64, 32, glm::vec3(3e38f)));
  IrrmapReport report;
  const Status error = RunIrrmap(QuickOptions(Path("bright.pfm"), Path("out")), report);
  ASSERT_FALSE(error.ok());
  EXPECT_EQ(error.error().code, DiagnosticCode::kBeyondFloatRange);
  EXPECT_THAT(error.message(), HasSubstr("bright.pfm"));
  EXPECT_THAT(error.message(), HasSubstr("beyond float range"));
  EXPECT_THAT(error.message(), HasSubstr("to 3e+38"));
  EXPECT_FALSE(fs::exists(Path("out")) && !fs::is_empty(Path("out")));
}

TEST_F(FloatRange, CoefficientsOnlyOfHugeTexelsFailsToo) {
  WritePfm(Path("bright.pfm"), LatLong(64, 32, glm::vec3(kFloatMax)));
  IrrmapOptions options = QuickOptions(Path("bright.pfm"), Path("out"));
  options.coefficients_only = true;
  IrrmapReport report;
  const Status error = RunIrrmap(options, report);
  ASSERT_FALSE(error.ok());
  EXPECT_THAT(error.message(), HasSubstr("beyond float range"));
}

TEST_F(FloatRange, TwoNeighbouringHugeTexelsGiveAFiniteAnswer) {
  Image image = LatLong(64, 32, glm::vec3(0.5f));
  image.at(20, 10) = image.at(21, 10) = glm::vec3(3e38f);
  WritePfm(Path("two.pfm"), image);
  IrrmapReport report;
  const Status error = RunIrrmap(QuickOptions(Path("two.pfm"), Path("out")), report);
  ASSERT_TRUE(error.ok()) << error.message();
  ExpectFiniteResults(report);
  EXPECT_THAT(ReadBytes(Path("out") / "coeffs.json"), Not(HasSubstr("null")));
  EXPECT_THAT(ReadBytes(Path("out") / "constants.vsh"), Not(::testing::ContainsRegex(",[ -]*(inf|nan)")));
}

TEST_F(FloatRange, ACrossWithOneTexelAtFloatMaxGivesAFiniteAnswer) {
  CubeMap cube = MakeTestCube(16);
  cube.face(CubeFace::kNegativeZ).at(3, 12) = glm::vec3(kFloatMax, 1.0f, kFloatMax);
  WritePfm(Path("cross.pfm"), CubeMapToImage(cube, EnvironmentLayout::kHorizontalCross));
  IrrmapReport report;
  const Status error = RunIrrmap(QuickOptions(Path("cross.pfm"), Path("out")), report);
  ASSERT_TRUE(error.ok()) << error.message();
  ExpectFiniteResults(report);
  EXPECT_EQ(report.texel_range.max, kFloatMax);
}

TEST_F(FloatRange, HugeNegativeTexelsAreClampedAndTheAnswerIsFinite) {
  Image image = LatLong(64, 32, glm::vec3(1.0f));
  for (int x = 0; x < 64; ++x) image.at(x, 5) = glm::vec3(-kFloatMax);
  WritePfm(Path("negative.pfm"), image);
  IrrmapReport report;
  const Status error = RunIrrmap(QuickOptions(Path("negative.pfm"), Path("out")), report);
  ASSERT_TRUE(error.ok()) << error.message();
  ExpectFiniteResults(report);
}

TEST_F(FloatRange, AnInMemoryCubeOfHugeTexelsFails) {
  // The Python module's project(): a cube in memory, no files.
  IrrmapOptions options = QuickOptions("array", Path("out"));
  options.cube = CubeMap(8);
  for (Image& face : options.cube->faces) {
    for (glm::vec3& texel : face.pixels) texel = glm::vec3(3e38f);
  }
  options.write_files = false;
  options.coefficients_only = true;
  IrrmapReport report;
  const Status error = RunIrrmap(options, report);
  ASSERT_FALSE(error.ok());
  EXPECT_THAT(error.message(), HasSubstr("texels from 3e+38 to 3e+38"));
}

TEST_F(FloatRange, BatchRecordsHoldOnlyFiniteNumbersAndFailTheOverflowingFile) {
  WritePfm(Path("a_bright.pfm"), LatLong(64, 32, glm::vec3(3e38f)));
  Image two = LatLong(64, 32, glm::vec3(0.5f));
  two.at(20, 10) = two.at(21, 10) = glm::vec3(3e38f);
  WritePfm(Path("b_two.pfm"), two);
  BatchOptions options;
  options.inputs = {Path("a_bright.pfm").string(), Path("b_two.pfm").string()};
  options.output = Path("out.jsonl");
  options.face_size = 32;
  options.threads = 1;
  BatchSummary summary;
  ASSERT_EQ(RunBatch(options, summary).message(), "");
  EXPECT_EQ(summary.succeeded, 1u);
  ASSERT_EQ(summary.failures.size(), 1u);
  EXPECT_THAT(summary.failures[0].input, HasSubstr("a_bright.pfm"));
  EXPECT_THAT(summary.failures[0].reason, HasSubstr("beyond float range (texels from 3e+38 to 3e+38)"));
  const std::string records = ReadBytes(Path("out.jsonl"));
  EXPECT_THAT(records, HasSubstr("b_two.pfm"));
  EXPECT_THAT(records, Not(HasSubstr("null")));
}

TEST_F(FloatRange, IrrmapExitsOneWithTheTexelRange) {
  WritePfm(Path("bright.pfm"), LatLong(64, 32, glm::vec3(3e38f)));
  const vs11::testing::CommandResult run = vs11::testing::RunIrrmap(
      fmt::format("'{}' --out '{}' --face-size 32 --map-size 4 --error-normals 20 --sphere-size 16",
                  Path("bright.pfm").string(), Path("out").string()));
  EXPECT_EQ(run.status, 1) << run.output;
  EXPECT_THAT(run.output, HasSubstr("texels from 3e+38 to 3e+38"));
  EXPECT_FALSE(fs::exists(Path("out")) && !fs::is_empty(Path("out")));
}

TEST(FloatRangeChecks, NullsOfNonFiniteNumbersAreFoundAtAnyDepth) {
  EXPECT_TRUE(AllNumbersFinite(nlohmann::ordered_json{{"a", {1.0, 2.0}}, {"b", "text"}}));
  EXPECT_FALSE(AllNumbersFinite(nlohmann::ordered_json{{"a", {1.0, std::nan("")}}}));
  EXPECT_FALSE(AllNumbersFinite(nlohmann::ordered_json{{"a", {{"b", -std::numeric_limits<double>::infinity()}}}}));
}

}  // namespace
}  // namespace vs11::irradiance
