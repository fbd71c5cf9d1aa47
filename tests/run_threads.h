// Runs a test body on several threads at once, for the concurrency tests that CI's ThreadSanitizer
// stage runs (.ci/tsan). The threads start together, so that their work overlaps instead of running
// one after the other as thread start-up would otherwise arrange.
#pragma once

#include <barrier>
#include <functional>
#include <thread>
#include <vector>

namespace vs11::testing {

// Calls body(t) for t = 0 .. threads - 1, each on its own thread, and returns once all are done.
// Assertions in `body` must be non-fatal (EXPECT_*): GoogleTest records them from any thread.
inline void RunOnThreads(int threads, const std::function<void(int thread_index)>& body) {
  std::barrier start(threads);
  std::vector<std::thread> workers;
  workers.reserve(static_cast<std::size_t>(threads));
  for (int t = 0; t < threads; ++t) {
    workers.emplace_back([&start, &body, t] {
      start.arrive_and_wait();
      body(t);
    });
  }
  for (std::thread& worker : workers) worker.join();
}

}  // namespace vs11::testing
