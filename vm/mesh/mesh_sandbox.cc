#include "vm/mesh/mesh_sandbox.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <exception>
#include <fstream>
#include <optional>
#include <stdexcept>
#include <thread>
#include <vector>

#include <fmt/format.h>

#include "vm/mesh/mesh_wire.h"

#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define VS11_UNDER_ASAN 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__)
#define VS11_UNDER_ASAN 1
#endif
#ifdef VS11_UNDER_ASAN
#include <sanitizer/common_interface_defs.h>
#endif

namespace vs11::mesh::internal {
namespace {

using Clock = std::chrono::steady_clock;

// The child writes to this descriptor (fixed, so that every other one can be closed).
constexpr int kReplyFd = 3;

std::string SignalName(int signal) {
  const char* abbreviation = sigabbrev_np(signal);
  return abbreviation != nullptr ? fmt::format("SIG{}", abbreviation) : fmt::format("signal {}", signal);
}

// Whole writes (the parent reads while the child writes); a failed write means the parent has gone
// or stopped reading, so the child ends.
void WriteAll(const char* data, std::size_t size) {
  while (size > 0) {
    const ssize_t written = write(kReplyFd, data, size);
    if (written < 0 && errno == EINTR) continue;
    if (written <= 0) _exit(3);
    data += written;
    size -= static_cast<std::size_t>(written);
  }
}

#ifndef VS11_UNDER_ASAN
// The address space in use now (the limit is set above it: the parent's mappings stay).
std::uintmax_t AddressSpaceInUse() {
  std::ifstream statm("/proc/self/statm");
  std::uintmax_t pages = 0;
  statm >> pages;
  return pages * static_cast<std::uintmax_t>(sysconf(_SC_PAGESIZE));
}
#endif

void PrepareChild(int write_fd, std::uintmax_t memory_limit) {
  for (int signal = 1; signal < NSIG; ++signal) {
    if (signal != SIGKILL && signal != SIGSTOP) ::signal(signal, SIG_DFL);
  }
  sigset_t none;
  sigemptyset(&none);
  sigprocmask(SIG_SETMASK, &none, nullptr);
  if (write_fd != kReplyFd && dup2(write_fd, kReplyFd) < 0) _exit(4);
  close_range(kReplyFd + 1, ~0U, 0);
  if (const int null = open("/dev/null", O_WRONLY); null >= 0) {
    dup2(null, STDOUT_FILENO);
    if (null != STDOUT_FILENO && null != kReplyFd) close(null);
  }
  const rlimit no_core = {0, 0};
  setrlimit(RLIMIT_CORE, &no_core);
#ifdef VS11_UNDER_ASAN
  // A sanitizer's report ends in its death callback, which libFuzzer (tests/fuzz) sets to save the
  // input being fuzzed as a crash-* file. Inherited across fork it would save one for a fault of
  // Assimp in this child, which the parent reports as that file's load error: the child dies
  // without it (the signals above are back to their defaults for the same reason).
  __sanitizer_set_death_callback(nullptr);
#endif
#ifndef VS11_UNDER_ASAN
  const std::uintmax_t in_use = AddressSpaceInUse();
  if (in_use > 0) {
    const rlim_t limit = static_cast<rlim_t>(in_use + memory_limit);
    const rlimit address_space = {limit, limit};
    setrlimit(RLIMIT_AS, &address_space);
  }
#else
  (void)memory_limit;
#endif
}

Diagnostic OutOfMemory(std::uintmax_t memory_limit) {
  return Failure(DiagnosticCode::kOutOfMemory,
                 fmt::format("out of memory while reading it (the reading process may use {} MiB more than the tool)",
                             memory_limit >> 20));
}

// The load's mesh or error, with its exceptions as errors.
Result<Mesh> LoadCatching(std::uintmax_t memory_limit, const std::function<Result<Mesh>(const StageReporter&)>& load) {
  try {
    return load([](LoadStage stage) {
      const char byte = static_cast<char>(stage);
      WriteAll(&byte, 1);
    });
  } catch (const std::bad_alloc&) {
    return OutOfMemory(memory_limit);
  } catch (const std::exception& e) {
    return Failure(DiagnosticCode::kCannotReadFile, fmt::format("reading it failed: {}", e.what()));
  }
}

[[noreturn]] void RunChild(int write_fd, std::uintmax_t memory_limit,
                           const std::function<Result<Mesh>(const StageReporter&)>& load) {
  PrepareChild(write_fd, memory_limit);
  const Result<Mesh> result = LoadCatching(memory_limit, load);
  std::string record;
  try {
    record = EncodeReplyRecord(result);
  } catch (const std::bad_alloc&) {
    record = EncodeReplyRecord(OutOfMemory(memory_limit));
  }
  WriteAll(record.data(), record.size());
  _exit(0);
}

// Waits for the child that has closed its end of the pipe; kills it if it lingers past `deadline`.
int WaitForChild(pid_t pid, Clock::time_point deadline) {
  int status = 0;
  for (;;) {
    const pid_t done = waitpid(pid, &status, WNOHANG);
    if (done == pid) return status;
    if (done < 0 && errno != EINTR) return 0;
    if (Clock::now() > deadline) {
      kill(pid, SIGKILL);
      while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
      }
      return status;
    }
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
}

void KillChild(pid_t pid) {
  kill(pid, SIGKILL);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
}

Diagnostic DeathError(const std::string& name, int status, char last_stage) {
  const std::string how = WIFSIGNALED(status) ? SignalName(WTERMSIG(status))
                          : WIFEXITED(status) ? fmt::format("exit status {}", WEXITSTATUS(status))
                                              : fmt::format("wait status {}", status);
  if (last_stage == static_cast<char>(LoadStage::kVs11)) {
    return Failure(DiagnosticCode::kMeshConverterCrashed,
                   fmt::format("vs11 crashed converting {} after Assimp read it ({}): a bug in vs11; please report "
                               "it with the file", name, how));
  }
  if (last_stage == static_cast<char>(LoadStage::kAssimp)) {
    return Failure(DiagnosticCode::kCannotReadFile,
                   fmt::format("Assimp crashed reading {} ({}); the file is corrupt or unsupported", name, how));
  }
  return Failure(DiagnosticCode::kCannotReadFile,
                 fmt::format("the process that reads {} ended before reading it ({})", name, how));
}

// Once `reply` holds the stage bytes and a record's header: reserves room for the whole record and
// returns whether that worked (false: the declared length is over the limit or the memory), or
// std::nullopt while the header is incomplete.
std::optional<bool> ReserveForRecord(std::vector<std::uint8_t>& reply) {
  std::size_t at = 0;
  while (at < reply.size() && (reply[at] == 'A' || reply[at] == 'V')) ++at;
  constexpr std::size_t kHeader = 1 + sizeof(std::uint64_t);
  if (reply.size() - at < kHeader) return std::nullopt;
  if (reply[at] != 'M' && reply[at] != 'E') return true;  // DecodeChildReply names the defect
  std::uint64_t length = 0;
  std::memcpy(&length, reply.data() + at + 1, sizeof length);
  if (length > kMaxReplyBytes) return false;
  try {
    reply.reserve(at + kHeader + static_cast<std::size_t>(length));
  } catch (const std::bad_alloc&) {
    return false;
  } catch (const std::length_error&) {
    return false;
  }
  return true;
}

// Reads the child's reply from `fd` into `reply` until the child closes its end: success then, or why
// the reading stopped before (the deadline passed, the reply outgrew the limits, the wait failed).
Status ReceiveReply(int fd, Clock::time_point deadline, double seconds, const std::string& name,
                    std::vector<std::uint8_t>& reply) {
  // A larger pipe means fewer turns between the processes (the default 64 KiB is kept on failure).
  fcntl(fd, F_SETPIPE_SZ, 1 << 20);
  std::array<std::uint8_t, 1 << 16> chunk;  // on the stack: a fresh heap buffer per load costs page faults
  std::optional<bool> reserved;  // unset until the record's header has arrived
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
    if (left <= 0) {
      const bool in_vs11 = DecodeChildReply(reply).last_stage == static_cast<char>(LoadStage::kVs11);
      return Failure(DiagnosticCode::kCannotReadFile,
                     fmt::format("reading {} did not finish within {} s ({}; the file may be corrupt, or raise the "
                                 "time limit with --mesh-timeout)", name, seconds,
                                 in_vs11 ? "in vs11's conversion, after Assimp read it" : "in Assimp's reader"));
    }
    pollfd wait_for = {fd, POLLIN, 0};
    const int ready = poll(&wait_for, 1, static_cast<int>(std::min<long long>(left, 1000)));
    if (ready < 0 && errno != EINTR) {
      return Failure(DiagnosticCode::kCannotReadFile,
                     fmt::format("{}: waiting for the process that reads it failed ({})", name, std::strerror(errno)));
    }
    if (ready <= 0) continue;
    const ssize_t got = read(fd, chunk.data(), chunk.size());
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) return {};  // end of file: the child has exited (or failed to read)
    if (reply.size() + static_cast<std::size_t>(got) > kMaxReplyBytes + 16) {
      return Failure(DiagnosticCode::kCannotReadFile,
                     fmt::format("{}: the mesh is larger than the loader's limits", name));
    }
    reply.insert(reply.end(), chunk.begin(), chunk.begin() + got);
    if (!reserved) {
      // The record's length is known once its header arrives: room for all of it at once spares
      // the copies (and on a virtual machine, the page faults) of a growing buffer.
      reserved = ReserveForRecord(reply);
      if (reserved.has_value() && !*reserved) {
        return Failure(DiagnosticCode::kCannotReadFile,
                       fmt::format("{}: the mesh is larger than the loader's limits or the memory", name));
      }
    }
  }
}

}  // namespace

double TimeLimitSeconds(const MeshLoadOptions& options, std::uintmax_t input_bytes) {
  if (options.timeout_seconds > 0) return options.timeout_seconds;
  return 60.0 + static_cast<double>(input_bytes) / (1 << 20);  // 60 s, plus 1 s per MiB
}

std::uintmax_t MemoryLimitBytes(const MeshLoadOptions& options, std::uintmax_t input_bytes) {
  if (options.memory_limit_bytes > 0) return options.memory_limit_bytes;
  return (std::uintmax_t{8} << 30) + 32 * input_bytes;  // 8 GiB, plus 32 bytes per byte of input
}

Result<Mesh> RunSandboxed(const std::string& name, std::uintmax_t input_bytes, const MeshLoadOptions& options,
                          const std::function<Result<Mesh>(const StageReporter&)>& load) {
  const double seconds = TimeLimitSeconds(options, input_bytes);
  const auto deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
  int fds[2];
  if (pipe2(fds, O_CLOEXEC) != 0) {
    return Failure(DiagnosticCode::kCannotReadFile,
                   fmt::format("{}: cannot make a pipe ({})", name, std::strerror(errno)));
  }
  // The child allocates (the loader, the reply), which after fork is safe in a single-threaded
  // parent; a parent with threads (irrmap batch --threads) is safe too as far as the heap goes,
  // because glibc's fork takes every malloc arena lock around the fork and the child starts with
  // them free. Any other lock another thread held at the fork stays held in the child for good: the
  // loader takes none the parent's threads hold (Assimp keeps no shared state here, OpenImageIO and
  // the thread pool are not called), and should one ever be taken the child blocks, which the
  // deadline below reports as a time-out rather than a hang.
  const pid_t pid = fork();
  if (pid < 0) {
    const int error = errno;
    close(fds[0]);
    close(fds[1]);
    return Failure(DiagnosticCode::kCannotReadFile,
                   fmt::format("{}: cannot start the process that reads it ({})", name, std::strerror(error)));
  }
  if (pid == 0) {
    close(fds[0]);
    RunChild(fds[1], MemoryLimitBytes(options, input_bytes), load);
  }
  close(fds[1]);

  std::vector<std::uint8_t> reply;
  const Status received = ReceiveReply(fds[0], deadline, seconds, name, reply);
  close(fds[0]);
  if (!received) {
    KillChild(pid);
    return received.error();
  }
  const int status = WaitForChild(pid, std::max(deadline, Clock::now() + std::chrono::seconds(5)));
  ChildReply decoded = DecodeChildReply(reply);
  reply = {};  // the mesh is held twice only while it is decoded
  if (decoded.complete && !decoded.malformed) {
    if (!decoded.result.ok() && decoded.result.error().message.find(name) == std::string::npos) {
      return Failure(decoded.result.error().code, fmt::format("{}: {}", name, decoded.result.error().message));
    }
    return std::move(decoded.result);
  }
  if (decoded.malformed) {
    return Failure(DiagnosticCode::kMeshWire,
                   fmt::format("{}: the process that reads it sent {}", name, decoded.result.error().message));
  }
  return DeathError(name, status, decoded.last_stage);
}

}  // namespace vs11::mesh::internal
