// irrmap loads OpenImageIO (its module and the ~260 libraries it brings) only when it reads or
// writes an image that needs it: the dynamic loader's own log (LD_DEBUG=libs) lists what it loaded.
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/run_tool.h"

namespace vs11::irradiance {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;
using vs11::testing::CommandResult;
using vs11::testing::RunCommandLine;
using IrrmapStartup = vs11::testing::ToolFolderTest;

// irrmap run with the dynamic loader's library log on stderr, captured with its output.
CommandResult RunLoggingLibraries(const std::string& args) {
  return RunCommandLine("LD_DEBUG=libs '" + std::string(VS11_BINARY_DIR) + "/irradiance/irrmap' " + args + " 2>&1");
}

TEST_F(IrrmapStartup, HelpLoadsNoOpenImageIo) {
  const CommandResult run = RunLoggingLibraries("--help");
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_THAT(run.output, HasSubstr("libhwy"));  // the log is there
  EXPECT_THAT(run.output, Not(HasSubstr("libOpenImageIO")));
  EXPECT_THAT(run.output, Not(HasSubstr("libvs11_image_io")));
}

TEST_F(IrrmapStartup, BuiltInEnvironmentCoefficientsLoadNoOpenImageIo) {
  const CommandResult run = RunLoggingLibraries("sky --face-size 16 --coefficients-only --no-ground-truth --out '" +
                                                (dir_ / "out").string() + "'");
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_THAT(run.output, Not(HasSubstr("libOpenImageIO")));
}

TEST_F(IrrmapStartup, AnImageFileLoadsTheModuleAndOpenImageIo) {
  // A 4:3 cross of 4 x 4 faces, PFM (read by OpenImageIO), grey.
  std::string pfm = "PF\n16 12\n-1.0\n";
  const float grey = 0.5f;
  for (int i = 0; i < 16 * 12 * 3; ++i) pfm.append(reinterpret_cast<const char*>(&grey), sizeof grey);
  const std::string input = Write("cross.pfm", pfm);
  const CommandResult run = RunLoggingLibraries("'" + input + "' --coefficients-only --no-ground-truth --out '" +
                                                (dir_ / "out").string() + "'");
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_THAT(run.output, HasSubstr("libvs11_image_io.so"));
  EXPECT_THAT(run.output, HasSubstr("libOpenImageIO"));
}

}  // namespace
}  // namespace vs11::irradiance
