// An exclusive lock on an output that one process at a time may write (irrmap batch's JSON Lines
// file, a --per-file folder): flock(2) on a lock file. The kernel releases a flock when its process
// ends, however it ends, so the lock of a process that died (SIGKILL, a lost node) never blocks the
// next run; a pid file would need guessing whether its pid is still the same process. The lock file
// says who holds it (pid, host, since when), for the error the next process gets, and is removed
// when the lock is released.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "vm/core/result.h"

namespace vs11::irradiance {

class OutputLock {
 public:
  // Takes the lock at `lock_file` (created if needed) without waiting. On failure an error:
  // "OUTPUT is in use by pid P on HOST since TIME (LOCK_FILE) ..." (kOutputInUse) when another
  // process holds it, else why the lock file cannot be made (kCannotWriteFile). `output` names what
  // is locked.
  static Result<OutputLock> Take(const std::filesystem::path& lock_file, const std::string& output);

  OutputLock(OutputLock&& other) noexcept;
  OutputLock& operator=(OutputLock&& other) noexcept;
  OutputLock(const OutputLock&) = delete;
  OutputLock& operator=(const OutputLock&) = delete;
  ~OutputLock();  // removes the lock file, then releases the lock

 private:
  OutputLock(int fd, std::filesystem::path path) : fd_(fd), path_(std::move(path)) {}
  void Release();

  int fd_ = -1;
  std::filesystem::path path_;
};

}  // namespace vs11::irradiance
