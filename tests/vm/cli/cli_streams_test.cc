// vs11's inputs and outputs as files, pipes and devices: every input read once ("-" and /dev/stdin
// work), devices and endless streams refused, no output that is an input, no partial set of outputs.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/run_tool.h"

namespace {

namespace fs = std::filesystem;

using ::testing::HasSubstr;
using vs11::testing::CommandResult;
using vs11::testing::RunVs11;
using vs11::testing::ToolFolderTest;

const std::string kVs11 = std::string(VS11_BINARY_DIR) + "/vm/vs11";
const std::string kProgram = "vs_1_1\ndcl_position v0\nadd oPos, v0, c0\nmov oD0, v0\n";
const std::string kConstants = "def c0, 1, 1, 1, 1\n";

// A shell command line (pipes, ulimit), stdout and stderr together. `timeout` ends a command that
// hangs on today's code (reading /dev/zero) instead of the whole suite.
CommandResult RunShell(const std::string& command) {
  return vs11::testing::RunCommandLine("timeout 60 sh -c '" + command + "' 2>&1");
}

std::string Read(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

class Vs11Streams : public ToolFolderTest {
 protected:
  void SetUp() override {
    ToolFolderTest::SetUp();
    program_ = Write("p.vsh", kProgram);
    constants_ = Write("c.vsh", kConstants);
    csv_ = Write("in.csv", "1,2,3,4\n5,6,7,8\n");
  }
  std::string program_, constants_, csv_;
};

TEST_F(Vs11Streams, APipedProgramIsReadOnceByPathOrAsDash) {
  for (const char* name : {"/dev/stdin", "-"}) {
    const CommandResult r = RunShell("cat " + program_ + " | " + kVs11 + " validate " + name);
    EXPECT_EQ(r.status, 0) << name << ": " << r.output;
    EXPECT_THAT(r.output, HasSubstr("valid vs_1_1")) << name;
  }
}

TEST_F(Vs11Streams, ConstantsAndVerticesComeFromStandardInput) {
  CommandResult r = RunShell("cat " + constants_ + " | " + kVs11 + " run " + program_ + " --consts - --input v0=" + csv_);
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("2,3,4,5"));
  r = RunShell("cat " + csv_ + " | " + kVs11 + " run " + program_ + " --consts " + constants_ + " --input v0=-");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("6,7,8,9"));
}

TEST_F(Vs11Streams, StandardInputTwiceIsAUsageError) {
  CommandResult r = RunShell("cat " + program_ + " | " + kVs11 + " run - --consts - --input v0=" + csv_);
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("can be read only once"));
  r = RunShell(kVs11 + " count --no-timing - - < " + program_);
  EXPECT_EQ(r.status, 2) << r.output;
}

TEST_F(Vs11Streams, DevicesAreRefusedBeforeAnythingIsRead) {
  const std::string run = "run " + program_ + " --consts ";
  const std::vector<std::string> commands = {"validate /dev/zero", "validate - < /dev/zero",
                                             run + "/dev/zero --input v0=" + csv_, run + constants_ + " --input v0=/dev/zero",
                                             "asm /dev/urandom -o " + (dir_ / "x.vso").string()};
  for (const std::string& args : commands) {
    const CommandResult r = RunShell(kVs11 + " " + args);
    EXPECT_EQ(r.status, 1) << args << ": " << r.output;
    EXPECT_THAT(r.output, HasSubstr("is a device")) << args;
  }
}

TEST_F(Vs11Streams, AnEndlessStreamStopsAtTheLimitOfItsKind) {
  CommandResult r = RunShell("yes \"; a comment\" | " + kVs11 + " validate -");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_THAT(r.output, HasSubstr("<stdin>: error: larger than the limit of 16 MiB"));
  r = RunShell("yes \"def c0, 1, 1, 1, 1\" | " + kVs11 + " run " + program_ + " --consts - --input v0=" + csv_);
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_THAT(r.output, HasSubstr("larger than the limit of 16 MiB"));
}

TEST_F(Vs11Streams, AsmDoesNotReplaceItsSourceHoweverTheOutputIsNamed) {
  fs::create_symlink(program_, dir_ / "link.vsh");
  for (const fs::path& output : {fs::path(program_), dir_ / "." / "p.vsh", dir_ / "link.vsh"}) {
    const CommandResult r = RunVs11("asm " + program_ + " -o " + output.string());
    EXPECT_EQ(r.status, 2) << output << ": " << r.output;
    EXPECT_THAT(r.output, HasSubstr("refusing to overwrite"));
    EXPECT_EQ(Read(program_), kProgram);
  }
  const CommandResult r = RunVs11("disasm " + program_ + " -o " + program_);
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_EQ(Read(program_), kProgram);
}

TEST_F(Vs11Streams, RunDoesNotOverwriteItsInputs) {
  const std::string run = "run " + program_ + " --consts " + constants_ + " --input v0=" + csv_;
  const std::string csv_text = Read(csv_);
  const std::vector<std::string> outputs = {"--out " + (dir_ / "." / "in.csv").string(), "--out " + constants_,
                                            "--out-buffer " + program_, "--trace 0 --trace-json " + csv_};
  for (const std::string& output : outputs) {
    const CommandResult r = RunVs11(run + " " + output);
    EXPECT_EQ(r.status, 2) << output << ": " << r.output;
    EXPECT_THAT(r.output, HasSubstr("refusing to overwrite")) << output;
  }
  EXPECT_EQ(Read(csv_), csv_text);
  EXPECT_EQ(Read(constants_), kConstants);
  EXPECT_EQ(Read(program_), kProgram);
}

TEST_F(Vs11Streams, RunDoesNotOverwriteAnNpyInputWithItsOutputArray) {
  const std::string folder = (dir_ / "arrays").string();
  ASSERT_EQ(RunVs11("run " + program_ + " --consts " + constants_ + " --input v0=" + csv_ + " --out-npy " + folder).status, 0);
  const std::string input = Read(dir_ / "arrays" / "oPos.npy");
  const CommandResult r =
      RunVs11("run " + program_ + " --npy v0=" + folder + "/oPos.npy --out-npy " + folder + "/.");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("refusing to overwrite"));
  EXPECT_EQ(Read(dir_ / "arrays" / "oPos.npy"), input);
}

TEST_F(Vs11Streams, OutputFilesThatDoNotAllFitLeaveNoneOfThem) {
  std::string rows;
  for (int i = 0; i < 1000; ++i) rows += "1,2,3,4\n";
  const std::string many = Write("many.csv", rows);
  const fs::path folder = dir_ / "out";
  fs::create_directories(folder);
  // The files may be at most 20 KiB: each .npy (16 KB) fits, the interleaved buffer (32 KB) does not.
  const CommandResult r = RunShell("trap \"\" XFSZ; ulimit -f 40; exec " + kVs11 + " run " + program_ + " --consts " +
                                   constants_ + " --input v0=" + many + " --out-npy " + folder.string() +
                                   " --out-buffer " + (folder / "all.bin").string());
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_TRUE(fs::is_empty(folder)) << (fs::is_empty(folder) ? "" : fs::directory_iterator(folder)->path().string());
}

}  // namespace
