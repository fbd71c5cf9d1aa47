#include "vm/core/atomic_file.h"

#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <climits>
#include <cstring>
#include <fstream>
#include <mutex>
#include <random>
#include <regex>
#include <set>
#include <system_error>

#include <fmt/format.h>

namespace vs11 {

namespace fs = std::filesystem;

namespace {

// The temporaries in the making, for the signal handler: fixed storage and lock-free atomics, the
// only things a handler may touch. A slot is claimed (kFree -> kBusy) before its path is written or
// compared, so only one thread ever uses a slot's path at a time.
constexpr int kTemporarySlots = 256;  // more at once are not removed on a signal, only by the next run
enum SlotState : int { kFree, kBusy, kLive };
struct TemporarySlot {
  std::atomic<int> state{kFree};
  char path[PATH_MAX];
};
TemporarySlot temporary_slots[kTemporarySlots];
static_assert(std::atomic<int>::is_always_lock_free, "the signal handler reads the slots");

std::string AbsolutePath(const fs::path& path) {
  std::error_code ignored;  // a relative path would do as well while the process stays in its folder
  const fs::path absolute = fs::absolute(path, ignored);
  return (absolute.empty() ? path : absolute).string();
}

void RegisterTemporary(const fs::path& temporary) {
  const std::string path = AbsolutePath(temporary);
  if (path.size() >= PATH_MAX) return;
  for (TemporarySlot& slot : temporary_slots) {
    int expected = kFree;
    if (!slot.state.compare_exchange_strong(expected, kBusy, std::memory_order_acquire)) continue;
    std::memcpy(slot.path, path.c_str(), path.size() + 1);
    slot.state.store(kLive, std::memory_order_release);
    return;
  }
}

void ForgetTemporary(const fs::path& temporary) {
  const std::string path = AbsolutePath(temporary);
  for (TemporarySlot& slot : temporary_slots) {
    int expected = kLive;
    if (!slot.state.compare_exchange_strong(expected, kBusy, std::memory_order_acquire)) continue;
    const bool same = path == slot.path;
    slot.state.store(same ? kFree : kLive, std::memory_order_release);
    if (same) return;
  }
}

constexpr int kCleanupSignals[] = {SIGINT, SIGTERM, SIGHUP};

extern "C" void RemoveTemporariesAndReraise(int signal) {
  const int saved_errno = errno;
  for (TemporarySlot& slot : temporary_slots) {
    if (slot.state.load(std::memory_order_acquire) == kLive) ::unlink(slot.path);
  }
  struct sigaction default_action {};
  default_action.sa_handler = SIG_DFL;
  sigemptyset(&default_action.sa_mask);
  ::sigaction(signal, &default_action, nullptr);
  errno = saved_errno;
  ::raise(signal);  // delivered when this handler returns (the signal is blocked until then)
}

// PID of a name TemporaryPathBeside made (".NAME.tmp-PID-SEED-N.EXT"), or nullopt.
std::optional<pid_t> TemporaryOwner(const std::string& name) {
  static const std::regex kTemporaryName(R"(^\..+\.tmp-([0-9]{1,9})-[0-9a-f]{8}-[0-9]+(\.[^.]*)?$)");
  std::smatch match;
  if (!std::regex_match(name, match, kTemporaryName)) return std::nullopt;
  return static_cast<pid_t>(std::stol(match[1].str()));
}

bool ProcessIsAlive(pid_t pid) { return pid == ::getpid() || ::kill(pid, 0) == 0 || errno != ESRCH; }

// RemoveStaleTemporaries, once per folder and process.
void RemoveStaleTemporariesOnce(const fs::path& folder) {
  static std::mutex mutex;
  static std::set<std::string> swept;
  {
    std::lock_guard<std::mutex> lock(mutex);
    if (!swept.insert(AbsolutePath(folder.empty() ? fs::path(".") : folder)).second) return;
  }
  RemoveStaleTemporaries(folder);
}

}  // namespace

fs::path TemporaryPathBeside(const fs::path& target) {
  static std::atomic<std::uint64_t> counter{0};
  static const std::uint32_t seed = std::random_device{}();
  RemoveStaleTemporariesOnce(target.parent_path());
  const std::string name = fmt::format(".{}.tmp-{}-{:08x}-{}{}", target.filename().string(), ::getpid(), seed,
                                       counter.fetch_add(1), target.extension().string());
  const fs::path temporary = target.parent_path() / name;
  RegisterTemporary(temporary);
  return temporary;
}

void RemoveQuietly(const fs::path& path) {
  std::error_code ignored;
  fs::remove(path, ignored);
  ForgetTemporary(path);
}

void RemoveTemporariesOnSignals() {
  for (int signal : kCleanupSignals) {
    struct sigaction current {};
    if (::sigaction(signal, nullptr, &current) != 0 || current.sa_handler == SIG_IGN) continue;  // nohup
    struct sigaction action {};
    action.sa_handler = RemoveTemporariesAndReraise;
    sigemptyset(&action.sa_mask);
    ::sigaction(signal, &action, nullptr);
  }
}

void RemoveStaleTemporaries(const fs::path& folder) {
  std::error_code error;
  const auto now = fs::file_time_type::clock::now();
  for (fs::directory_iterator it(folder.empty() ? fs::path(".") : folder, error), end; !error && it != end;
       it.increment(error)) {
    const std::optional<pid_t> owner = TemporaryOwner(it->path().filename().string());
    if (!owner || ProcessIsAlive(*owner)) continue;
    std::error_code ignored;
    const fs::file_time_type written = fs::last_write_time(it->path(), ignored);
    if (!ignored && now - written > kStaleTemporaryAge && it->is_regular_file(ignored)) fs::remove(it->path(), ignored);
  }
}

Status CommitRenames(std::span<const PendingRename> renames, std::vector<fs::path>* renamed) {
  for (std::size_t i = 0; i < renames.size(); ++i) {
    std::error_code error;
    fs::rename(renames[i].temporary, renames[i].target, error);
    if (!error) ForgetTemporary(renames[i].temporary);
    if (error) {
      for (std::size_t j = i; j < renames.size(); ++j) RemoveQuietly(renames[j].temporary);
      return Failure(DiagnosticCode::kCannotWriteFile, fmt::format("cannot rename the finished file into {} ({})",
                                                                   renames[i].target.string(), error.message()));
    }
    if (renamed != nullptr) renamed->push_back(renames[i].target);
  }
  return {};
}

namespace {

// Writes `bytes` to a new temporary beside `path`: the temporary, or the error (and none is left).
Status WriteTemporary(const fs::path& path, std::string_view bytes, fs::path& temporary) {
  temporary = TemporaryPathBeside(path);
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) {
      const fs::path folder = path.parent_path().empty() ? fs::path(".") : path.parent_path();
      RemoveQuietly(temporary);  // not there, but registered
      return Failure(DiagnosticCode::kCannotWriteFile,
                     fmt::format("{}: cannot create a file in {}", path.string(), folder.string()));
    }
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    out.flush();
    if (!out) {
      out.close();
      RemoveQuietly(temporary);
      return Failure(DiagnosticCode::kCannotWriteFile, fmt::format("{}: write failed", path.string()));
    }
  }
  return {};
}

}  // namespace

Status WriteFilesAtomically(std::span<const FileToWrite> files) {
  std::vector<PendingRename> renames;
  for (const FileToWrite& file : files) {
    fs::path temporary;
    if (Status written = WriteTemporary(file.path, file.bytes, temporary); !written) {
      for (const PendingRename& pending : renames) RemoveQuietly(pending.temporary);
      return written;
    }
    renames.push_back({temporary, file.path});
  }
  return CommitRenames(renames);
}

Status WriteFileAtomically(const fs::path& path, std::string_view bytes) {
  const FileToWrite file[] = {{path, bytes}};
  return WriteFilesAtomically(file);
}

Status WriteFileAtomically(const fs::path& path, std::span<const std::uint8_t> bytes) {
  return WriteFileAtomically(path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

}  // namespace vs11
