// irrmap's outputs end to end: `irrmap batch -o` that is not a regular file is refused with a clear
// error (no abort, no endless read).
#include <sys/stat.h>

#include <string>

#include "irradiance/io/environment_io.h"
#include "irradiance/io/environments.h"
#include "tests/irradiance/io/environment_test_support.h"
#include "tests/run_tool.h"

namespace vs11::irradiance {
namespace {

using namespace envtest;
using ::testing::HasSubstr;
using ::testing::Not;
using IrrmapOutputs = TempFolderTest;
using vs11::testing::CommandResult;
using vs11::testing::RunIrrmap;

TEST_F(IrrmapOutputs, BatchOutputThatIsNotARegularFileIsRefused) {
  ASSERT_EQ(WriteCrossExr(MakeSky(8), Path("sky.exr")), std::nullopt);
  fs::create_directories(Path("folder"));
  ASSERT_EQ(mkfifo(Path("fifo").c_str(), 0644), 0);
  const std::vector<std::pair<std::string, std::string>> outputs = {
      {Path("folder").string(), "is a folder"},
      {"/dev/zero", "is not a regular file"},
      {Path("fifo").string(), "is not a regular file"},
  };
  for (const auto& [output, reason] : outputs) {
    for (const std::string resume : {" --resume", ""}) {
      const CommandResult run = RunIrrmap(fmt::format("batch '{}' -o '{}'{}", Path("sky.exr").string(), output, resume));
      EXPECT_EQ(run.status, 1) << output << resume << "\n" << run.output;
      EXPECT_THAT(run.output, HasSubstr(output + " " + reason)) << resume;
      EXPECT_THAT(run.output, Not(HasSubstr("terminate"))) << output << resume;
    }
  }
  EXPECT_TRUE(fs::is_empty(Path("folder")));
}

}  // namespace
}  // namespace vs11::irradiance
