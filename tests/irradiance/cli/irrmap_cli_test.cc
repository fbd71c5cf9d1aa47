// The irrmap tool end to end on hostile environment files: exit code, message, and no output files.
#include <cstdio>
#include <limits>
#include <string>

#include "irradiance/io/environment_io.h"
#include "tests/irradiance/io/environment_test_support.h"
#include "tests/run_tool.h"

namespace vs11::irradiance {
namespace {

using namespace envtest;
using ::testing::HasSubstr;
using IrrmapCli = TempFolderTest;

using vs11::testing::CommandResult;
using vs11::testing::RunIrrmap;

// Small and quick: a 4 x 4 face, few error normals, small previews.
std::string QuickRun(const fs::path& input, const fs::path& out) {
  return fmt::format("'{}' --out '{}' --map-size 4 --error-normals 20 --sphere-size 16",
                     input.string(), out.string());
}

TEST_F(IrrmapCli, TruncatedFileFailsWithTheReasonAndWritesNothing) {
  // A float TIFF: OpenImageIO's read_image succeeds on a short one and only records the error.
  const Image cross = CubeMapToImage(MakeTestCube(4), EnvironmentLayout::kHorizontalCross);
  ASSERT_EQ(WriteImage(cross, Path("sky.tif")).message(), "");
  const std::string bytes = ReadBytes(Path("sky.tif"));
  WriteBytes(Path("sky.tif"), bytes.substr(0, bytes.size() * 2 / 3));
  const CommandResult run = RunIrrmap(QuickRun(Path("sky.tif"), Path("out")));
  EXPECT_NE(run.status, 0);
  EXPECT_THAT(run.output, HasSubstr("sky.tif"));
  EXPECT_THAT(run.output, HasSubstr("truncated"));
  EXPECT_FALSE(fs::exists(Path("out")) && !fs::is_empty(Path("out")));
}

TEST_F(IrrmapCli, HugeHeaderFailsWithoutAllocatingAndWritesNothing) {
  WriteBytes(Path("huge.pfm"), "PF\n1073741824 1073741824\n-1.0\n" + std::string(4096, '\0'));
  const CommandResult run = RunIrrmap(QuickRun(Path("huge.pfm"), Path("out")));
  EXPECT_NE(run.status, 0);
  EXPECT_THAT(run.output, HasSubstr("huge.pfm"));
  EXPECT_THAT(run.output, HasSubstr("larger than"));
  EXPECT_FALSE(fs::exists(Path("out")) && !fs::is_empty(Path("out")));
}

TEST_F(IrrmapCli, NanTexelsAreZeroedWithAWarningAndTheRunSucceeds) {
  CubeMap cube = MakeTestCube(4);
  cube.face(CubeFace::kPositiveZ).at(2, 1).r = std::numeric_limits<float>::quiet_NaN();
  cube.face(CubeFace::kNegativeX).at(0, 3).b = -3.0f;
  ASSERT_EQ(WriteCrossExr(cube, Path("sky.exr")).message(), "");
  const CommandResult run = RunIrrmap(QuickRun(Path("sky.exr"), Path("out")));
  EXPECT_EQ(run.status, 0) << run.output;
  EXPECT_THAT(run.output, HasSubstr("warning"));
  EXPECT_THAT(run.output, HasSubstr("2 of 192 texels had NaN, infinite or negative values"));
  EXPECT_TRUE(fs::exists(Path("out") / "coeffs.json"));
}

TEST_F(IrrmapCli, ASquareImageIsAUsageErrorAskingForTheLayout) {
  ASSERT_TRUE(WriteFloatImage(Path("cube_px.exr"), Image(16, 16, glm::vec3(1.0f))));
  const CommandResult run = RunIrrmap(QuickRun(Path("cube_px.exr"), Path("out")));
  EXPECT_EQ(run.status, 2) << run.output;
  EXPECT_THAT(run.output, HasSubstr("cube_px.exr: cannot tell the layout of a square 16 x 16 image"));
  EXPECT_THAT(run.output, HasSubstr("--layout angular"));
  EXPECT_FALSE(fs::exists(Path("out")) && !fs::is_empty(Path("out")));
  const CommandResult named = RunIrrmap(QuickRun(Path("cube_px.exr"), Path("out")) + " --layout angular --face-size 4");
  EXPECT_EQ(named.status, 0) << named.output;
  EXPECT_THAT(named.output, HasSubstr("layout angular (as given)"));
}

TEST_F(IrrmapCli, TheReportSaysWhichLayoutWasDetectedAndWhy) {
  WritePfm(Path("lat.pfm"), Image(16, 8, glm::vec3(1.0f)));
  const CommandResult run = RunIrrmap(QuickRun(Path("lat.pfm"), Path("out")) + " --face-size 4");
  EXPECT_EQ(run.status, 0) << run.output;
  EXPECT_THAT(run.output, HasSubstr("layout latlong (detected from the 2:1 aspect ratio of the 16 x 8 image)"));
}

}  // namespace
}  // namespace vs11::irradiance
