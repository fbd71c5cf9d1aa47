#include "vm/core/atomic_file.h"

#include <unistd.h>

#include <atomic>
#include <fstream>
#include <random>
#include <system_error>

#include <fmt/format.h>

namespace vs11 {

namespace fs = std::filesystem;

fs::path TemporaryPathBeside(const fs::path& target) {
  static std::atomic<std::uint64_t> counter{0};
  static const std::uint32_t seed = std::random_device{}();
  const std::string name = fmt::format(".{}.tmp-{}-{:08x}-{}{}", target.filename().string(), ::getpid(), seed,
                                       counter.fetch_add(1), target.extension().string());
  return target.parent_path() / name;
}

void RemoveQuietly(const fs::path& path) {
  std::error_code ignored;
  fs::remove(path, ignored);
}

std::optional<std::string> CommitRenames(std::span<const PendingRename> renames, std::vector<fs::path>* renamed) {
  for (std::size_t i = 0; i < renames.size(); ++i) {
    std::error_code error;
    fs::rename(renames[i].temporary, renames[i].target, error);
    if (error) {
      for (std::size_t j = i; j < renames.size(); ++j) RemoveQuietly(renames[j].temporary);
      return fmt::format("cannot rename the finished file into {} ({})", renames[i].target.string(),
                         error.message());
    }
    if (renamed != nullptr) renamed->push_back(renames[i].target);
  }
  return std::nullopt;
}

std::optional<std::string> WriteFileAtomically(const fs::path& path, std::string_view bytes) {
  const fs::path temporary = TemporaryPathBeside(path);
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) {
      const fs::path folder = path.parent_path().empty() ? fs::path(".") : path.parent_path();
      return fmt::format("{}: cannot create a file in {}", path.string(), folder.string());
    }
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    out.flush();
    if (!out) {
      out.close();
      RemoveQuietly(temporary);
      return fmt::format("{}: write failed", path.string());
    }
  }
  const PendingRename rename[] = {{temporary, path}};
  return CommitRenames(rename);
}

std::optional<std::string> WriteFileAtomically(const fs::path& path, std::span<const std::uint8_t> bytes) {
  return WriteFileAtomically(path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

}  // namespace vs11
