// The output lock. See output_lock.h.
#include "irradiance/jobs/output_lock.h"

#include <fcntl.h>
#include <limits.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <ctime>
#include <thread>
#include <utility>

#include <fmt/chrono.h>
#include <fmt/format.h>

namespace vs11::irradiance {
namespace {

// The holder's line is short; more than this is not a lock file of ours, and is not quoted whole.
constexpr std::size_t kMaxHolderBytes = 512;
// A lock file replaced again and again between our open and our lock (each holder removes it when it
// ends) is retried this often before giving up.
constexpr int kLockAttempts = 100;
// The holder writes its line right after it locks: a reader that finds the file still empty waits this
// long, in steps, before it says so instead of naming the holder.
constexpr int kHolderReadAttempts = 20;
constexpr std::chrono::milliseconds kHolderReadStep{5};

std::string Holder() {
  char host[HOST_NAME_MAX + 1] = {};
  if (gethostname(host, sizeof host - 1) != 0) std::strcpy(host, "an unknown host");
  const std::time_t now = std::time(nullptr);
  std::tm local{};
  localtime_r(&now, &local);
  return fmt::format("pid {} on {} since {:%Y-%m-%d %H:%M:%S %z}", getpid(), host, local);
}

std::string ReadHolder(int fd) {
  char buffer[kMaxHolderBytes] = {};
  const ssize_t size = pread(fd, buffer, sizeof buffer, 0);
  std::string text(buffer, size > 0 ? static_cast<std::size_t>(size) : 0);
  while (!text.empty() && (text.back() == '\n' || text.back() == '\0')) text.pop_back();
  return text;
}

std::string AwaitHolder(int fd) {
  std::string holder = ReadHolder(fd);
  for (int attempt = 1; holder.empty() && attempt < kHolderReadAttempts; ++attempt) {
    std::this_thread::sleep_for(kHolderReadStep);
    holder = ReadHolder(fd);
  }
  return holder;
}

// Whether `fd` is still the file at `path`: a holder that ended removed it after we opened it, and
// a lock on the removed file would lock nothing another process can see.
bool IsStillAt(int fd, const std::filesystem::path& path) {
  struct stat opened {}, named {};
  return fstat(fd, &opened) == 0 && stat(path.c_str(), &named) == 0 && opened.st_dev == named.st_dev &&
         opened.st_ino == named.st_ino;
}

}  // namespace

Result<OutputLock> OutputLock::Take(const std::filesystem::path& lock_file, const std::string& output) {
  for (int attempt = 0; attempt < kLockAttempts; ++attempt) {
    const int fd = open(lock_file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK, 0644);
    if (fd < 0) {
      return Failure(DiagnosticCode::kCannotWriteFile,
                     fmt::format("cannot create the lock file {} ({})", lock_file.string(), std::strerror(errno)));
    }
    if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const int code = errno;
      const std::string holder = code == EWOULDBLOCK ? AwaitHolder(fd) : std::string();
      close(fd);
      if (code != EWOULDBLOCK) {
        return Failure(DiagnosticCode::kCannotWriteFile,
                       fmt::format("cannot lock {} ({})", lock_file.string(), std::strerror(code)));
      }
      return Failure(DiagnosticCode::kOutputInUse,
                     fmt::format("{} is in use by another irrmap batch: {} (lock file {}); wait for it to end or stop "
                                 "it (the lock of a process that has ended is free)",
                                 output, holder.empty() ? "a process that has not yet written its pid" : holder,
                                 lock_file.string()));
    }
    if (!IsStillAt(fd, lock_file)) {
      close(fd);
      continue;
    }
    const std::string holder = Holder() + "\n";
    if (ftruncate(fd, 0) != 0 || pwrite(fd, holder.data(), holder.size(), 0) != static_cast<ssize_t>(holder.size())) {
      const int code = errno;
      unlink(lock_file.c_str());
      close(fd);
      return Failure(DiagnosticCode::kCannotWriteFile,
                     fmt::format("cannot write the lock file {} ({})", lock_file.string(), std::strerror(code)));
    }
    return OutputLock(fd, lock_file);
  }
  return Failure(DiagnosticCode::kCannotWriteFile,
                 fmt::format("cannot lock {}: the lock file keeps being replaced", lock_file.string()));
}

OutputLock::OutputLock(OutputLock&& other) noexcept
    : fd_(std::exchange(other.fd_, -1)), path_(std::move(other.path_)) {}

OutputLock& OutputLock::operator=(OutputLock&& other) noexcept {
  if (this != &other) {
    Release();
    fd_ = std::exchange(other.fd_, -1);
    path_ = std::move(other.path_);
  }
  return *this;
}

OutputLock::~OutputLock() { Release(); }

void OutputLock::Release() {
  if (fd_ < 0) return;
  // Removed while still held: a process waiting to lock the old file finds it gone and makes a new one.
  unlink(path_.c_str());
  close(fd_);
  fd_ = -1;
}

}  // namespace vs11::irradiance
