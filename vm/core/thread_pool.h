// A persistent pool of worker threads, started once and shared by every parallel call (the engines,
// the SH projection, the ground truth, `irrmap batch`), so that a process never holds more busy
// threads than the pool has and no call pays for starting a thread (about 26 us each).
//
// A call hands the pool `count` tasks; the calling thread runs tasks itself and idle workers help.
// Because the caller takes tasks too, a call always finishes even when every worker is busy, and a
// task may make a parallel call of its own (nested use, as `irrmap batch` running an engine does):
// the inner call runs on its caller and whichever workers are free, and cannot deadlock.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <mutex>
#include <thread>
#include <type_traits>
#include <utility>
#include <vector>

namespace vs11 {

// The most threads a caller may ask the engines for (the tools' --threads, the Python module's threads=).
inline constexpr int kMaxThreadsOption = 256;

class ThreadPool {
 public:
  // A pool whose calls run on up to `threads` threads: the caller and `threads - 1` workers
  // (`threads` < 1 counts as 1: no workers, every task runs on its caller). Where the system refuses
  // a thread, the pool keeps the workers it has (threads() says how many), with a warning on stderr:
  // never an exception.
  explicit ThreadPool(int threads);
  ~ThreadPool();  // waits for the workers; no call may be in flight
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  // The process-wide pool that a library function uses when its caller passes none: one thread per
  // core (std::thread::hardware_concurrency), made on first use, joined at exit. Passing a pool of
  // one's own instead is always possible; this one exists so that callers who do not care still
  // share one set of threads.
  static ThreadPool& Default();

  // The most threads one call runs on (the caller included).
  int threads() const { return static_cast<int>(workers_.size()) + 1; }

  // Runs task(index, slot) for every index in [0, count) and returns when all have finished. The
  // tasks run on the calling thread and on up to `max_threads - 1` workers (capped by threads()),
  // each index exactly once, in no fixed order. `slot` in [0, max_threads) names the thread within
  // this call: two tasks with the same slot never run at once, so per-slot scratch needs no lock.
  // Slot 0 is the caller. If tasks throw, the remaining tasks still run and the first exception is
  // rethrown here. Safe to call from several threads at once and from inside a task.
  template <class Task>
  void Run(std::size_t count, int max_threads, Task&& task) {
    using TaskType = std::remove_reference_t<Task>;
    RunErased(count, max_threads, &task, [](void* context, std::size_t index, int slot) {
      (*static_cast<TaskType*>(context))(index, slot);
    });
  }

 private:
  using TaskFunction = void (*)(void* context, std::size_t index, int slot);

  // One Run call: lives on its caller's stack; the queue points to it while it has unclaimed tasks.
  struct Call {
    void* context;
    TaskFunction function;
    std::size_t count;
    int max_threads;
    std::size_t next_index = 0;  // the next unclaimed task
    std::size_t finished = 0;    // tasks done (the caller returns when this reaches count)
    int joined = 1;              // threads that have taken a slot (the caller holds slot 0)
    std::exception_ptr error = nullptr;  // the first exception a task threw
  };

  void RunErased(std::size_t count, int max_threads, void* context, TaskFunction function);
  // Runs `call`'s unclaimed tasks as `slot` until none are left; `lock` is held on entry and exit.
  void RunTasks(Call& call, int slot, std::unique_lock<std::mutex>& lock);
  void WorkerLoop();

  std::mutex mutex_;
  std::condition_variable work_ready_;     // a call was queued, or the pool is stopping
  std::condition_variable call_finished_;  // some call's last task finished
  std::deque<Call*> queue_;                // calls with tasks left that may take another thread
  bool stopping_ = false;
  std::vector<std::thread> workers_;
};

}  // namespace vs11
