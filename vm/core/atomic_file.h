// Writing files so that a reader never sees a half-written one and a failure leaves nothing behind:
// every output is written to a temporary beside its target, then renamed over it (a rename within
// one folder is atomic on POSIX file systems, and a temporary beside the target is in its folder).
#pragma once

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "vm/core/result.h"

namespace vs11 {

// A fresh hidden name beside `target`: ".NAME.tmp-PID-SEED-N.EXT". Unique within the process (N
// counts) and across processes (PID and a random SEED); the target's extension stays last, for
// writers that choose a format by it.
std::filesystem::path TemporaryPathBeside(const std::filesystem::path& target);

// Removes `path` if it exists. Errors are ignored: this is clean-up after a failure already reported.
void RemoveQuietly(const std::filesystem::path& path);

// Every path TemporaryPathBeside gives is registered until CommitRenames renames it or RemoveQuietly
// removes it. After this call (once, at the start of a tool's main), SIGINT, SIGTERM and SIGHUP
// first remove every registered temporary and then end the process as the signal would have; a
// signal the caller ignores stays ignored. Libraries leave the signals to their host (Python's
// KeyboardInterrupt), so nothing installs this implicitly.
void RemoveTemporariesOnSignals();

// Temporaries that only a process killed outright (SIGKILL, a crash, a power cut) leaves behind:
// one whose PID is no live process here and that nobody has written for this long. The age keeps
// a run on another machine that shares the folder (its PID means nothing here) safe: a temporary
// being written is written to continually.
inline constexpr std::chrono::minutes kStaleTemporaryAge{10};

// Removes the stale temporaries (kStaleTemporaryAge) of TemporaryPathBeside's form in `folder`.
// TemporaryPathBeside calls it once per folder and process. Errors are ignored.
void RemoveStaleTemporaries(const std::filesystem::path& folder);

struct PendingRename {
  std::filesystem::path temporary;  // written and closed
  std::filesystem::path target;
};

// Renames each finished temporary over its target, in order. On the first failure, removes every
// temporary not yet renamed and returns the error "cannot rename the finished file into TARGET
// (why)" (kCannotWriteFile); targets renamed before it stay. `renamed`, when given, receives each
// target renamed.
Status CommitRenames(std::span<const PendingRename> renames, std::vector<std::filesystem::path>* renamed = nullptr);

// Writes several files, all or none: every one is written to its temporary first, and only when all
// are written are they renamed into place (CommitRenames). On a failure to write (a full disk, a
// read-only folder) no target is touched and no temporary is left.
struct FileToWrite {
  std::filesystem::path path;
  std::string_view bytes;
};
Status WriteFilesAtomically(std::span<const FileToWrite> files);

// Writes `bytes` to `path` through a temporary: on failure `path` is untouched and no temporary is
// left. The error (kCannotWriteFile) names `path` and what failed.
Status WriteFileAtomically(const std::filesystem::path& path, std::string_view bytes);
Status WriteFileAtomically(const std::filesystem::path& path, std::span<const std::uint8_t> bytes);

}  // namespace vs11
