// irrmap's outputs end to end: `irrmap batch -o` that is not a regular file is refused with a clear
// error (no abort, no endless read), and a second `irrmap` run into one folder says in coeffs.json
// which files it wrote and names the files of an earlier run that it did not replace.
#include <sys/stat.h>

#include <string>

#include <nlohmann/json.hpp>

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
  ASSERT_EQ(WriteCrossExr(MakeSky(8), Path("sky.exr")).message(), "");
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

TEST_F(IrrmapOutputs, ASecondRunNamesTheFilesOfTheFirstThatItDidNotReplace) {
  const std::string out = Path("out").string();
  const CommandResult full = RunIrrmap(fmt::format("sky --face-size 8 --map-size 4 --no-ground-truth --out '{}'", out));
  ASSERT_EQ(full.status, 0) << full.output;
  EXPECT_THAT(full.output, Not(HasSubstr("earlier run")));
  nlohmann::json coefficients = nlohmann::json::parse(ReadBytes(Path("out") / "coeffs.json"));
  EXPECT_EQ(coefficients["files"],
            (nlohmann::json{"coeffs.json", "constants.vsh", "program.vsh", "irradiance.exr"}));

  const CommandResult second = RunIrrmap(fmt::format("spot --face-size 8 --coefficients-only --out '{}'", out));
  ASSERT_EQ(second.status, 0) << second.output;
  EXPECT_THAT(second.output, HasSubstr("warning: " + (Path("out") / "irradiance.exr").string() +
                                       " is left from an earlier run"));
  coefficients = nlohmann::json::parse(ReadBytes(Path("out") / "coeffs.json"));
  EXPECT_EQ(coefficients["files"], (nlohmann::json{"coeffs.json", "constants.vsh", "program.vsh"}));

  const CommandResult third =
      RunIrrmap(fmt::format("sky --face-size 8 --map-size 4 --map-format dds --no-ground-truth --out '{}'", out));
  ASSERT_EQ(third.status, 0) << third.output;
  EXPECT_THAT(third.output, HasSubstr((Path("out") / "irradiance.exr").string() + " is left from an earlier run"));
  EXPECT_THAT(third.output, Not(HasSubstr("irradiance.dds is left")));
}

}  // namespace
}  // namespace vs11::irradiance
