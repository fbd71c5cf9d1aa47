// Runs the built tools (vs11, irrmap) for end-to-end tests, stdout and stderr captured together.
#pragma once

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace vs11::testing {

struct CommandResult {
  int status = -1;
  std::string output;  // stdout and stderr together
};

// `tool` is the executable's path inside the build folder.
inline CommandResult RunTool(const std::string& tool, const std::string& args) {
  std::string command = std::string(VS11_BINARY_DIR) + "/" + tool + " " + args + " 2>&1";
  CommandResult result;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return result;
  std::array<char, 4096> buffer;
  while (std::size_t n = std::fread(buffer.data(), 1, buffer.size(), pipe)) result.output.append(buffer.data(), n);
  int status = pclose(pipe);
  result.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

inline CommandResult RunVs11(const std::string& args) { return RunTool("vm/vs11", args); }
inline CommandResult RunIrrmap(const std::string& args) { return RunTool("irradiance/irrmap", args); }

}  // namespace vs11::testing
