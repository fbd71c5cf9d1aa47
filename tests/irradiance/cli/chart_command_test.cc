// `irrmap chart` as a user runs it: the binary (built before the tests, tests/CMakeLists.txt).
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <random>
#include <string>

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include "tests/run_tool.h"

namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

using vs11::testing::CommandResult;
using vs11::testing::RunIrrmap;

class ChartCommand : public testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(fs::exists(std::string(VS11_BINARY_DIR) + "/irradiance/irrmap"));
    folder_ = fs::path(testing::TempDir()) / fmt::format("vs11_chart_command_{:x}", std::random_device{}());
    fs::remove_all(folder_);
  }
  void TearDown() override { fs::remove_all(folder_); }
  fs::path folder_;
};

TEST_F(ChartCommand, WritesTheCsvAndBothImagesAndPrintsTheTable) {
  const CommandResult r = RunIrrmap(fmt::format(
      "chart sky constant --face-size 4 --error-normals 16 --min-batch-ms 0 --batches 1 --threads 1 --out {}",
      folder_.string()));
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* name : {"speed_accuracy.csv", "speed_accuracy.svg", "speed_accuracy.png"}) {
    EXPECT_TRUE(fs::is_regular_file(folder_ / name)) << name;
  }
  EXPECT_THAT(r.output, HasSubstr("sky          direct     2       1x1"));
}

TEST_F(ChartCommand, AnUnknownEnvironmentFailsWithoutOutput) {
  const CommandResult r = RunIrrmap(fmt::format("chart no_such_file.exr --face-size 4 --out {}", folder_.string()));
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_THAT(r.output, HasSubstr("irrmap: error:"));
  EXPECT_THAT(r.output, HasSubstr("no_such_file.exr"));
  EXPECT_FALSE(fs::exists(folder_ / "speed_accuracy.csv"));
}

TEST_F(ChartCommand, HelpDescribesTheMethods) {
  const CommandResult r = RunIrrmap("chart --help");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("--min-batch-ms"));
  EXPECT_THAT(r.output, HasSubstr("direct  the basis evaluated at level k's texel centres"));
}

}  // namespace
