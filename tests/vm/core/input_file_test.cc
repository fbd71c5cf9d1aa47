// Inputs read once, with a limit, devices refused; outputs that are inputs recognised however named.
#include "vm/core/input_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace vs11 {
namespace {

namespace fs = std::filesystem;

class InputFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::path(::testing::TempDir()) / (std::string("input_file_") + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path Write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name, std::ios::binary) << text;
    return dir_ / name;
  }
  fs::path dir_;
};

// A pipe holding `text` with its writing end closed, named by path as /dev/stdin or <(...) name one.
class FilledPipe {
 public:
  explicit FilledPipe(const std::string& text) {
    EXPECT_EQ(::pipe(fds_), 0);
    EXPECT_EQ(::write(fds_[1], text.data(), text.size()), static_cast<ssize_t>(text.size()));
    ::close(fds_[1]);
  }
  ~FilledPipe() { ::close(fds_[0]); }
  fs::path path() const { return "/proc/self/fd/" + std::to_string(fds_[0]); }

 private:
  int fds_[2] = {-1, -1};
};

TEST_F(InputFileTest, ReadsARegularFileWhole) {
  const Result<std::string> read = ReadInputFile(Write("p.vsh", "vs.1.1\nmov oPos, v0\n"), kMaxProgramFileBytes);
  ASSERT_TRUE(read.ok()) << read.message();
  EXPECT_EQ(*read, "vs.1.1\nmov oPos, v0\n");
}

TEST_F(InputFileTest, ReadsAPipeGivenByPath) {
  FilledPipe pipe("vs_1_1\n");
  const Result<std::string> read = ReadInputFile(pipe.path(), kMaxProgramFileBytes);
  ASSERT_TRUE(read.ok()) << read.message();
  EXPECT_EQ(*read, "vs_1_1\n");
}

TEST_F(InputFileTest, AStreamLongerThanTheLimitIsAnErrorNamingTheLimit) {
  FilledPipe pipe(std::string(3 << 10, 'x'));
  const Result<std::string> read = ReadInputFile(pipe.path(), 1 << 10);
  ASSERT_FALSE(read.ok());
  EXPECT_EQ(read.error().code, DiagnosticCode::kCannotReadFile);
  EXPECT_NE(read.message().find("larger than the limit"), std::string::npos) << read.message();
}

TEST_F(InputFileTest, AFileLargerThanTheLimitIsRefusedBeforeItIsRead) {
  const Result<std::string> read = ReadInputFile(Write("big.csv", std::string(2 << 20, '1')), 1 << 20);
  ASSERT_FALSE(read.ok());
  EXPECT_EQ(read.error().code, DiagnosticCode::kCannotReadFile);
  EXPECT_NE(read.message().find("limit of 1 MiB"), std::string::npos) << read.message();
}

TEST_F(InputFileTest, DevicesFoldersAndMissingFilesAreRefusedWithTheReason) {
  const std::vector<std::pair<fs::path, std::string>> cases = {
      {"/dev/zero", "is a device"}, {"/dev/null", "is a device"}, {dir_, "is a folder"}, {dir_ / "no", "no such file"}};
  for (const auto& [path, reason] : cases) {
    const Result<std::string> read = ReadInputFile(path, kMaxProgramFileBytes);
    ASSERT_FALSE(read.ok()) << path;
    EXPECT_EQ(read.error().code, DiagnosticCode::kCannotReadFile);
    EXPECT_NE(read.message().find(reason), std::string::npos) << path << ": " << read.message();
  }
}

TEST_F(InputFileTest, ImagesNeedARegularFileButProgramsTakePipes) {
  FilledPipe pipe("x");
  EXPECT_TRUE(InputFileProblem(Write("a.pfm", "x"), false).ok());
  EXPECT_EQ(InputFileProblem(pipe.path(), false).message(), "is a named pipe (FIFO), not a regular file");
  EXPECT_EQ(InputFileProblem(pipe.path(), false).error().code, DiagnosticCode::kCannotReadFile);
  EXPECT_TRUE(InputFileProblem(pipe.path(), true).ok());
  EXPECT_EQ(InputFileProblem("/dev/zero", true).message(), "is a device, not a file or a pipe");
}

TEST_F(InputFileTest, StandardInputIsNamedForMessages) {
  EXPECT_EQ(InputDisplayName("-"), "<stdin>");
  EXPECT_EQ(InputDisplayName("a.vsh"), "a.vsh");
}

TEST_F(InputFileTest, AnOutputIsRecognisedAsAnInputHoweverItIsSpelled) {
  const fs::path input = Write("in.csv", "1,2,3\n");
  fs::create_symlink(input, dir_ / "link.csv");
  fs::create_hard_link(input, dir_ / "hard.csv");
  const std::vector<fs::path> inputs = {dir_ / "other.csv", input};
  for (const fs::path& output : {input, dir_ / "." / "in.csv", dir_ / "link.csv", dir_ / "hard.csv",
                                 dir_ / ".." / dir_.filename() / "in.csv"}) {
    const Status error = OutputOverwritesInput(output, inputs);
    ASSERT_FALSE(error.ok()) << output;
    EXPECT_EQ(error.error().code, DiagnosticCode::kOutputOverwritesInput);
    EXPECT_NE(error.message().find("refusing to overwrite"), std::string::npos) << error.message();
  }
}

TEST_F(InputFileTest, NewOutputsAndStandardStreamsAreNoInputs) {
  const fs::path input = Write("in.csv", "1\n");
  const std::vector<fs::path> inputs = {input, "-"};
  EXPECT_TRUE(OutputOverwritesInput(dir_ / "new.csv", inputs).ok());
  EXPECT_TRUE(OutputOverwritesInput(Write("other.csv", "1\n"), inputs).ok());
  EXPECT_TRUE(OutputOverwritesInput("-", inputs).ok());
}

}  // namespace
}  // namespace vs11
