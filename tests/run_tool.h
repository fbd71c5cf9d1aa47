// Runs the built tools (vs11, irrmap) for end-to-end tests, stdout and stderr captured together.
#pragma once

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

namespace vs11::testing {

struct CommandResult {
  int status = -1;
  std::string output;  // stdout and stderr together
};

// A shell command line, stdout and stderr captured together.
inline CommandResult RunCommandLine(const std::string& command_line) {
  const std::string command = command_line + " 2>&1";
  CommandResult result;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return result;
  std::array<char, 4096> buffer;
  while (std::size_t n = std::fread(buffer.data(), 1, buffer.size(), pipe)) result.output.append(buffer.data(), n);
  int status = pclose(pipe);
  result.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

// `tool` is the executable's path inside the build folder.
inline CommandResult RunTool(const std::string& tool, const std::string& args) {
  return RunCommandLine(std::string(VS11_BINARY_DIR) + "/" + tool + " " + args);
}

inline CommandResult RunVs11(const std::string& args) { return RunTool("vm/vs11", args); }

// A fresh folder per test (named after it) for the files a tool reads and writes; removed after.
class ToolFolderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = std::filesystem::path(::testing::TempDir()) /
           ("vs11_tool_" + std::string(info->test_suite_name()) + "_" + info->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  // Writes `text` to `name` in the folder; returns its path.
  std::string Write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name, std::ios::binary) << text;
    return (dir_ / name).string();
  }
  std::filesystem::path dir_;
};
inline CommandResult RunIrrmap(const std::string& args) { return RunTool("irradiance/irrmap", args); }

}  // namespace vs11::testing
