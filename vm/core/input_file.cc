#include "vm/core/input_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <system_error>

#include <fmt/format.h>

namespace vs11 {
namespace {

namespace fs = std::filesystem;

constexpr std::size_t kReadChunkBytes = std::size_t{1} << 16;

bool IsStandardInput(const fs::path& path) { return path.native() == kStandardInputName; }

// The error of an input file that cannot be read (every error here).
Diagnostic Unreadable(std::string message) { return Failure(DiagnosticCode::kCannotReadFile, std::move(message)); }

// What is wrong with a file of this mode, or success. A terminal is accepted: `vs11 validate -`
// typed at the keyboard ends at Ctrl-D.
Status ModeProblem(mode_t mode, bool is_terminal, bool pipes_allowed) {
  const char* kind = nullptr;
  if (S_ISREG(mode)) return {};
  if (S_ISFIFO(mode) || (S_ISCHR(mode) && is_terminal)) {
    if (pipes_allowed) return {};
    kind = "is a named pipe (FIFO)";
  } else if (S_ISDIR(mode)) {
    kind = "is a folder";
  } else if (S_ISCHR(mode) || S_ISBLK(mode)) {
    kind = "is a device";
  } else if (S_ISSOCK(mode)) {
    kind = "is a socket";
  } else {
    kind = "is of an unknown kind";
  }
  return Unreadable(fmt::format("{}, not a {}", kind, pipes_allowed ? "file or a pipe" : "regular file"));
}

Diagnostic TooLarge(std::size_t max_bytes) {
  return Unreadable(fmt::format("larger than the limit of {} MiB for this kind of file", max_bytes >> 20));
}

// Reads `fd` to its end, failing past `max_bytes`.
Result<std::string> ReadDescriptor(int fd, std::size_t max_bytes, std::size_t expected_size) {
  std::string bytes;
  bytes.reserve(std::min(expected_size, max_bytes) + 1);
  char chunk[kReadChunkBytes];
  for (;;) {
    const ssize_t got = ::read(fd, chunk, sizeof chunk);
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) return Unreadable(fmt::format("read failed ({})", std::strerror(errno)));
    if (got == 0) break;
    if (bytes.size() + static_cast<std::size_t>(got) > max_bytes) return TooLarge(max_bytes);
    bytes.append(chunk, static_cast<std::size_t>(got));
  }
  return bytes;
}

// Reads the open `fd` once its kind and size are checked.
Result<std::string> ReadOpened(int fd, std::size_t max_bytes) {
  struct stat status {};
  if (::fstat(fd, &status) != 0) return Unreadable(fmt::format("cannot read the file ({})", std::strerror(errno)));
  if (Status problem = ModeProblem(status.st_mode, ::isatty(fd) == 1, true); !problem.ok()) return problem.error();
  if (S_ISREG(status.st_mode) && static_cast<std::uintmax_t>(status.st_size) > max_bytes) return TooLarge(max_bytes);
  return ReadDescriptor(fd, max_bytes, S_ISREG(status.st_mode) ? static_cast<std::size_t>(status.st_size) : 0);
}

}  // namespace

std::string InputDisplayName(const fs::path& path) { return IsStandardInput(path) ? "<stdin>" : path.string(); }

Status InputFileProblem(const fs::path& path, bool pipes_allowed) {
  struct stat status {};
  if (::stat(path.c_str(), &status) != 0) {
    return Failure(DiagnosticCode::kCannotReadFile, errno == ENOENT ? "no such file" : std::strerror(errno));
  }
  return ModeProblem(status.st_mode, false, pipes_allowed);
}

Result<std::string> ReadInputFile(const fs::path& path, std::size_t max_bytes) {
  const bool standard_input = IsStandardInput(path);
  // Opening a device can have effects (a tape rewinds); a path is looked at before it is opened.
  if (!standard_input) {
    struct stat status {};
    if (::stat(path.c_str(), &status) != 0) {
      return Unreadable(
          fmt::format("cannot read the file ({})", errno == ENOENT ? "no such file" : std::strerror(errno)));
    }
    if (S_ISBLK(status.st_mode) || S_ISDIR(status.st_mode) || S_ISSOCK(status.st_mode)) {
      return ModeProblem(status.st_mode, false, true).error();
    }
  }
  const int fd = standard_input ? STDIN_FILENO : ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOCTTY);
  if (fd < 0) return Unreadable(fmt::format("cannot read the file ({})", std::strerror(errno)));
  Result<std::string> result = ReadOpened(fd, max_bytes);
  if (!standard_input) ::close(fd);
  return result;
}

Status OutputOverwritesInput(const fs::path& output, std::span<const fs::path> inputs) {
  if (output.empty() || IsStandardInput(output)) return {};
  for (const fs::path& input : inputs) {
    if (input.empty() || IsStandardInput(input)) continue;
    std::error_code error;  // set when either does not exist: then they are not one file
    if (fs::equivalent(output, input, error) && !error) {
      return Failure(DiagnosticCode::kOutputOverwritesInput,
                     fmt::format("{} is the input {}: refusing to overwrite it", output.string(), input.string()));
    }
  }
  return {};
}

}  // namespace vs11
