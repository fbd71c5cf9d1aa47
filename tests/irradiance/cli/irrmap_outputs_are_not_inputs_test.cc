// irrmap never writes over one of its inputs: an environment file that has an output's name in the
// output folder (however the folder is spelled), or batch's -o naming an input or a list.
#include <string>

#include "irradiance/io/environment_io.h"
#include "tests/irradiance/io/environment_test_support.h"
#include "tests/run_tool.h"

namespace vs11::irradiance {
namespace {

using namespace envtest;
using ::testing::HasSubstr;
using IrrmapOutputsAreNotInputs = TempFolderTest;

using vs11::testing::CommandResult;
using vs11::testing::RunIrrmap;

// A cross-layout image where irrmap writes its irradiance map: out/irradiance.exr.
fs::path EnvironmentNamedLikeAnOutput(const fs::path& folder) {
  fs::create_directories(folder);
  const fs::path path = folder / "irradiance.exr";
  EXPECT_EQ(WriteImage(CubeMapToImage(MakeTestCube(4), EnvironmentLayout::kHorizontalCross), path).message(), "");
  return path;
}

TEST_F(IrrmapOutputsAreNotInputs, AnEnvironmentInTheOutputFolderWithAnOutputsNameIsRefusedBeforeAnyWork) {
  const fs::path input = EnvironmentNamedLikeAnOutput(Path("out"));
  const std::string before = ReadBytes(input);
  for (const fs::path& out : {Path("out"), Path("out") / ".", Path("out") / ".." / "out"}) {
    const CommandResult run = RunIrrmap(fmt::format("'{}' --out '{}' --no-ground-truth", input.string(), out.string()));
    EXPECT_EQ(run.status, 2) << out << ": " << run.output;
    EXPECT_THAT(run.output, HasSubstr("refusing to overwrite"));
    EXPECT_EQ(ReadBytes(input), before);
  }
  EXPECT_FALSE(fs::exists(Path("out") / "coeffs.json"));
}

TEST_F(IrrmapOutputsAreNotInputs, AnEnvironmentInTheOutputFolderThatNoOutputReplacesIsRead) {
  const fs::path input = EnvironmentNamedLikeAnOutput(Path("out"));
  // --coefficients-only writes no irradiance map.
  EXPECT_EQ(RunIrrmap(fmt::format("'{}' --out '{}' --coefficients-only", input.string(), Path("out").string())).status, 0);
  fs::rename(input, Path("out") / "sky.exr");
  const CommandResult run =
      RunIrrmap(fmt::format("'{}' --out '{}' --no-ground-truth", (Path("out") / "sky.exr").string(), Path("out").string()));
  EXPECT_EQ(run.status, 0) << run.output;
}

TEST_F(IrrmapOutputsAreNotInputs, BatchRefusesAnOutputThatIsAnInputOrAListAndLeavesItWhole) {
  const fs::path input = EnvironmentNamedLikeAnOutput(Path("in"));
  const std::string before = ReadBytes(input);
  CommandResult run = RunIrrmap(fmt::format("batch '{}' -o '{}' --resume", input.string(), (Path("in") / "." / "irradiance.exr").string()));
  EXPECT_EQ(run.status, 2) << run.output;
  EXPECT_THAT(run.output, HasSubstr("refusing to overwrite"));
  EXPECT_EQ(ReadBytes(input), before);

  WriteBytes(Path("list.txt"), input.string() + "\n");
  const std::string list = ReadBytes(Path("list.txt"));
  run = RunIrrmap(fmt::format("batch --list '{}' -o '{}' --resume", Path("list.txt").string(), Path("list.txt").string()));
  EXPECT_EQ(run.status, 2) << run.output;
  EXPECT_EQ(ReadBytes(Path("list.txt")), list);
}

}  // namespace
}  // namespace vs11::irradiance
