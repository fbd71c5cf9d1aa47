#include "vm/core/thread_pool.h"

#include <algorithm>
#include <cstdio>
#include <exception>

namespace vs11 {

ThreadPool::ThreadPool(int threads) {
  for (int t = 1; t < threads; ++t) {
    try {
      workers_.emplace_back([this] { WorkerLoop(); });
    } catch (const std::exception& error) {
      // Out of threads (std::system_error: RLIMIT_NPROC, a cgroup's pids.max) or of memory for a stack: the pool
      // runs on the threads it has, down to its callers alone, which every call takes part in.
      std::fprintf(stderr, "warning: could start only %d of %d threads (%s); running on %d\n", t, threads,
                   error.what(), t);
      break;
    }
  }
}

ThreadPool::~ThreadPool() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  work_ready_.notify_all();
  for (std::thread& worker : workers_) worker.join();
}

ThreadPool& ThreadPool::Default() {
  static ThreadPool pool(static_cast<int>(std::max(1u, std::thread::hardware_concurrency())));
  return pool;
}

void ThreadPool::RunErased(std::size_t count, int max_threads, void* context, TaskFunction function) {
  if (count == 0) return;
  Call call{.context = context, .function = function, .count = count, .max_threads = std::max(1, max_threads)};
  std::unique_lock lock(mutex_);
  // One thread, or one task: the caller runs it all and wakes nobody.
  if (count == 1 || call.max_threads == 1 || workers_.empty()) {
    RunTasks(call, 0, lock);
    lock.unlock();
    if (call.error) std::rethrow_exception(call.error);
    return;
  }
  queue_.push_back(&call);
  const std::size_t helpers =
      std::min({count - 1, static_cast<std::size_t>(call.max_threads - 1), workers_.size()});
  lock.unlock();
  if (helpers == workers_.size()) {
    work_ready_.notify_all();
  } else {
    for (std::size_t k = 0; k < helpers; ++k) work_ready_.notify_one();
  }
  lock.lock();
  RunTasks(call, 0, lock);
  // Tasks other threads took may still be running: `call` lives on this stack until they finish.
  call_finished_.wait(lock, [&call] { return call.finished == call.count; });
  lock.unlock();
  if (call.error) std::rethrow_exception(call.error);
}

void ThreadPool::RunTasks(Call& call, int slot, std::unique_lock<std::mutex>& lock) {
  while (call.next_index < call.count) {
    const std::size_t index = call.next_index++;
    if (call.next_index == call.count) std::erase(queue_, &call);  // nothing left to hand out
    lock.unlock();
    std::exception_ptr error;
    try {
      call.function(call.context, index, slot);
    } catch (...) {
      error = std::current_exception();
    }
    lock.lock();
    if (error && !call.error) call.error = error;
    if (++call.finished == call.count) call_finished_.notify_all();
  }
}

void ThreadPool::WorkerLoop() {
  std::unique_lock lock(mutex_);
  while (true) {
    work_ready_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
    if (stopping_) return;
    // The oldest call first: a nested call queued later waits behind the call that made it, whose
    // caller works through it in any case.
    Call& call = *queue_.front();
    const int slot = call.joined++;
    // The call's last slot is taken: no further thread may join it.
    if (call.joined == call.max_threads) std::erase(queue_, &call);
    RunTasks(call, slot, lock);
  }
}

}  // namespace vs11
