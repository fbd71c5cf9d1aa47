// irrmap's command line: --version, usage errors (status 2, in every subcommand, bad option values
// too; a failed input stays 1), the output folder checked before any work, --face-size against a cube-map file, --no-ground-truth; and the basis pyramid's progress.
#include <string>

#include "irradiance/io/environments.h"
#include "irradiance/sh/sh_projection.h"
#include "tests/irradiance/io/environment_test_support.h"
#include "tests/run_tool.h"

namespace vs11::irradiance {
namespace {

using namespace envtest;
using ::testing::HasSubstr;
using ::testing::Not;
using IrrmapUsage = TempFolderTest;
using vs11::testing::CommandResult;
using vs11::testing::RunIrrmap;

TEST_F(IrrmapUsage, VersionAndUsageErrors) {
  const CommandResult version = RunIrrmap("--version");
  EXPECT_EQ(version.status, 0) << version.output;
  EXPECT_THAT(version.output, HasSubstr("irrmap "));
  const CommandResult flag = RunIrrmap("--frobnicate");
  EXPECT_EQ(flag.status, 2);
  EXPECT_THAT(flag.output, HasSubstr("--frobnicate"));
  EXPECT_EQ(RunIrrmap("--face-size notanumber").status, 2);
}

// A bad option value is a usage error (2) wherever it is given, checked before any work; an input or
// output that fails is 1.
TEST_F(IrrmapUsage, EveryBadOptionValueOfEverySubcommandExitsTwo) {
  ASSERT_EQ(WriteCrossExr(MakeSky(8), Path("sky.exr")).message(), "");
  const std::string batch = fmt::format("batch '{}' -o '{}' ", Path("sky.exr").string(), Path("out.jsonl").string());
  const std::string single = fmt::format("sky --face-size 16 --coefficients-only --out '{}' ", Path("out").string());
  const std::string chart = fmt::format("chart sky --face-size 16 --out '{}' ", Path("chart").string());
  const std::string stability = fmt::format("stability --out '{}' ", Path("stability").string());
  const std::vector<std::string> usage_errors = {
      batch + "--layout bogus", batch + "--error-metric x", batch + "--face-size 3", batch + "--max-error nan",
      batch + "--max-error 1", batch + "--threads -1", batch + "--shard 2/2", fmt::format("batch -o '{}'", Path("o.jsonl").string()),
      single + "--layout bogus", single + "--error-metric x", single + "--face-size 3", single + "--max-error nan",
      single + "--threads -1", single + "--engine foo", single + "--window x", single + "--order x",
      single + "--map-size 0", single + "--map-format png", single + "--sh-export foo", single + "--window-width 0",
      single + "--sphere-size 1", single + "--error-normals 0",
      chart + "--layout bogus", chart + "--error-metric x", chart + "--face-size 3", chart + "--threads -1",
      chart + "--batches 0", chart + "--min-batch-ms nan",
      stability + "--face-size 3", stability + "--max-error nan", stability + "--error-metric x",
      stability + "--threads -1", stability + "--error-normals 3"};
  for (const std::string& command : usage_errors) {
    const CommandResult run = RunIrrmap(command);
    EXPECT_EQ(run.status, 2) << command << "\n" << run.output;
    EXPECT_THAT(run.output, HasSubstr("irrmap: error: ")) << command;
    EXPECT_THAT(run.output, HasSubstr("Run with --help")) << command;
  }
  EXPECT_FALSE(fs::exists(Path("out.jsonl")));
  for (const std::string& command :
       {fmt::format("{}'{}'", batch, Path("missing.exr").string()),
        fmt::format("{}'{}'", single.substr(4), Path("missing.exr").string()),
        fmt::format("batch '{}' -o '{}'", Path("*.none").string(), Path("none.jsonl").string())}) {
    const CommandResult run = RunIrrmap(command);
    EXPECT_EQ(run.status, 1) << command << "\n" << run.output;
  }
  for (const char* help : {"--help", "batch --help", "chart --help", "stability --help"}) {
    EXPECT_THAT(RunIrrmap(help).output, HasSubstr("Exit status: 0 success, 1 ")) << help;
  }
}

// Every choice flag of every subcommand parses with its name table: an unknown name is a usage error
// that lists the valid names.
TEST_F(IrrmapUsage, AnUnknownChoiceListsTheValidNames) {
  const std::string out = fmt::format("--out '{}' ", Path("out").string());
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"--layout bogus", "unknown layout 'bogus' (use auto, faces, hcross, vcross, hstrip, vstrip, latlong or angular)"},
      {"--error-metric x", "unknown error metric 'x' (use relative, peak or rms)"},
      {"--order x", "unknown order 'x' (use auto, order0, order1, zh3 or order2)"},
      {"--window x", "unknown window 'x' (use none, hanning, lanczos, dering or nonneg)"},
      {"--map-format png", "unknown map format 'png' (use exr, dds, ktx2, ktx or hdr-faces)"},
      {"--sh-export three,foo", "unknown --sh-export format 'foo' (use three, filament, unity, gltf, glsl or hlsl)"},
      {"batch x -o y --layout bogus", "unknown layout 'bogus' (use auto, "},
      {"batch x -o y --order x", "unknown order 'x' (use auto, order0, "},
      {"batch x -o y --window x", "unknown window 'x' (use none, "},
      {"batch x -o y --error-metric x", "unknown error metric 'x' (use relative, "},
      {"chart sky --layout bogus", "unknown layout 'bogus' (use auto, "},
      {"chart sky --error-metric x", "unknown error metric 'x' (use relative, "},
      {"stability --error-metric x", "unknown error metric 'x' (use relative, "}};
  for (const auto& [command, message] : cases) {
    const CommandResult run = RunIrrmap(command.starts_with("batch") ? command : command + " " + out);
    EXPECT_EQ(run.status, 2) << command << "\n" << run.output;
    EXPECT_THAT(run.output, HasSubstr(message)) << command;
  }
  EXPECT_FALSE(fs::exists(Path("out")));
}

TEST_F(IrrmapUsage, AnOutputPathThatIsAFileFailsBeforeAnyWork) {
  WriteBytes(Path("afile"), "not a folder");
  for (const std::string& command :
       {fmt::format("--face-size 16 --coefficients-only --out '{}'", Path("afile").string()),
        fmt::format("--face-size 16 --out '{}'", (Path("afile") / "below").string()),
        fmt::format("chart sky --face-size 16 --out '{}'", Path("afile").string()),
        fmt::format("stability --out '{}'", Path("afile").string())}) {
    const CommandResult run = RunIrrmap(command);
    EXPECT_EQ(run.status, 1) << command;
    // The check's own message, not the writer's after the work (which would also print results).
    EXPECT_THAT(run.output, HasSubstr("afile is not a directory")) << command << "\n" << run.output;
    EXPECT_THAT(run.output, Not(HasSubstr("stage times"))) << command;
    EXPECT_THAT(run.output, Not(HasSubstr("irrmap chart: sky"))) << command;  // the sweep's progress
  }
  EXPECT_EQ(ReadBytes(Path("afile")), "not a folder");
}

TEST_F(IrrmapUsage, FaceSizeWithACubeMapFileIsWarnedAbout) {
  ASSERT_EQ(WriteCubeMap(MakeSky(8), Path("cross.exr"), EnvironmentLayout::kHorizontalCross).message(), "");
  const std::string base = fmt::format("'{}' --coefficients-only --out '{}'", Path("cross.exr").string(),
                                       Path("out").string());
  const CommandResult warned = RunIrrmap(base + " --face-size 64");
  EXPECT_EQ(warned.status, 0) << warned.output;
  EXPECT_THAT(warned.output, HasSubstr("--face-size 64 ignored"));
  EXPECT_THAT(warned.output, HasSubstr("faces of 8x8"));
  EXPECT_THAT(RunIrrmap(base).output, Not(HasSubstr("ignored")));
  EXPECT_THAT(RunIrrmap(base + " --face-size 8").output, Not(HasSubstr("ignored")));
}

TEST_F(IrrmapUsage, NoGroundTruthWritesTheMapButNoErrorsOrPreview) {
  const CommandResult run =
      RunIrrmap(fmt::format("sky --face-size 16 --map-size 4 --no-ground-truth --out '{}'", Path("out").string()));
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_TRUE(fs::exists(Path("out") / "irradiance.exr"));
  EXPECT_TRUE(fs::exists(Path("out") / "constants.vsh"));
  EXPECT_FALSE(fs::exists(Path("out") / "preview.png"));
  EXPECT_THAT(run.output, Not(HasSubstr("ground_truth")));
  const std::string json = ReadBytes(Path("out") / "coeffs.json");
  EXPECT_THAT(json, HasSubstr("estimated_error"));
  EXPECT_THAT(json, Not(HasSubstr("max_relative_error")));
}

TEST(BasisPyramidProgress, ReportsEachTileUpToOne) {
  // 256 is cut into 8 x 8 tiles of 32 x 32 texels.
  std::vector<double> fractions;
  std::optional<BasisPyramid> pyramid = BuildBasisPyramid(256, 2, [&](double f) { fractions.push_back(f); });
  ASSERT_TRUE(pyramid);
  ASSERT_EQ(fractions.size(), 64u);
  for (std::size_t i = 0; i < fractions.size(); ++i) EXPECT_DOUBLE_EQ(fractions[i], (i + 1) / 64.0);
}

}  // namespace
}  // namespace vs11::irradiance
