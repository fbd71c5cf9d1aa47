#include "vm/core/regular_file.h"

#include <system_error>

namespace vs11 {

std::optional<std::string> WhyNotARegularFile(const std::filesystem::path& path) {
  namespace fs = std::filesystem;
  std::error_code error;
  const fs::file_status status = fs::status(path, error);
  if (error && status.type() != fs::file_type::not_found) return "cannot be read (" + error.message() + ")";
  switch (status.type()) {
    case fs::file_type::regular: return std::nullopt;
    case fs::file_type::not_found: return "no such file";
    case fs::file_type::directory: return "a folder, not a regular file";
    case fs::file_type::fifo: return "a named pipe (FIFO), not a regular file";
    case fs::file_type::character: return "a character device, not a regular file";
    case fs::file_type::block: return "a block device, not a regular file";
    case fs::file_type::socket: return "a socket, not a regular file";
    default: return "not a regular file";
  }
}

}  // namespace vs11
