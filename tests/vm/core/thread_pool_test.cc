#include "vm/core/thread_pool.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

namespace vs11 {
namespace {

// How long a test waits for the pool's workers to join in before it calls the pool serial: far
// beyond any wake-up, short enough that a broken pool fails instead of hanging the suite.
constexpr auto kJoinTimeout = std::chrono::seconds(20);

TEST(ThreadPool, RunsEveryTaskExactlyOnce) {
  ThreadPool pool(4);
  for (const std::size_t count : {0u, 1u, 2u, 3u, 4u, 5u, 100u, 10007u}) {
    std::vector<std::atomic<int>> runs(count);
    pool.Run(count, 4, [&](std::size_t index, int) { runs[index].fetch_add(1); });
    for (std::size_t i = 0; i < count; ++i) EXPECT_EQ(runs[i].load(), 1) << "task " << i << " of " << count;
  }
}

TEST(ThreadPool, SlotsStayBelowMaxThreadsAndAreNeverSharedAtOnce) {
  ThreadPool pool(4);
  for (const int max_threads : {1, 2, 3, 4, 8}) {
    std::vector<std::atomic<int>> busy(static_cast<std::size_t>(max_threads));
    std::atomic<int> overlaps = 0, out_of_range = 0;
    pool.Run(2000, max_threads, [&](std::size_t, int slot) {
      if (slot < 0 || slot >= max_threads) {
        out_of_range.fetch_add(1);
        return;
      }
      if (busy[static_cast<std::size_t>(slot)].fetch_add(1) != 0) overlaps.fetch_add(1);
      std::this_thread::yield();
      busy[static_cast<std::size_t>(slot)].fetch_sub(1);
    });
    EXPECT_EQ(out_of_range.load(), 0) << "max_threads " << max_threads;
    EXPECT_EQ(overlaps.load(), 0) << "max_threads " << max_threads;
  }
}

// Two tasks that each wait for the other can only finish when two threads run them at once.
TEST(ThreadPool, RunsTasksOnWorkersAtOnce) {
  ThreadPool pool(2);
  ASSERT_EQ(pool.threads(), 2);
  std::atomic<int> started = 0;
  std::atomic<bool> met = true;
  std::vector<std::thread::id> ran_on(2);
  pool.Run(2, 2, [&](std::size_t index, int) {
    ran_on[index] = std::this_thread::get_id();
    started.fetch_add(1);
    const auto deadline = std::chrono::steady_clock::now() + kJoinTimeout;
    while (started.load() < 2) {
      if (std::chrono::steady_clock::now() > deadline) {
        met = false;
        return;
      }
      std::this_thread::yield();
    }
  });
  EXPECT_TRUE(met.load());
  EXPECT_NE(ran_on[0], ran_on[1]);
}

TEST(ThreadPool, OneThreadRunsEverythingOnTheCaller) {
  for (const auto& [pool_threads, max_threads] : {std::pair{1, 4}, std::pair{4, 1}, std::pair{0, 2}}) {
    ThreadPool pool(pool_threads);
    std::atomic<int> elsewhere = 0, nonzero_slot = 0;
    const std::thread::id caller = std::this_thread::get_id();
    pool.Run(50, max_threads, [&](std::size_t, int slot) {
      if (std::this_thread::get_id() != caller) elsewhere.fetch_add(1);
      if (slot != 0) nonzero_slot.fetch_add(1);
    });
    EXPECT_EQ(elsewhere.load(), 0) << "pool " << pool_threads << ", max_threads " << max_threads;
    EXPECT_EQ(nonzero_slot.load(), 0) << "pool " << pool_threads << ", max_threads " << max_threads;
  }
}

TEST(ThreadPool, RethrowsTheFirstExceptionAfterEveryTaskRan) {
  for (const int threads : {1, 3}) {
    ThreadPool pool(threads);
    std::atomic<int> ran = 0;
    EXPECT_THROW(pool.Run(64, threads,
                          [&](std::size_t index, int) {
                            ran.fetch_add(1);
                            if (index % 7 == 3) throw std::runtime_error("task " + std::to_string(index));
                          }),
                 std::runtime_error);
    EXPECT_EQ(ran.load(), 64) << threads << " threads";
    // The pool is still usable.
    std::atomic<int> after = 0;
    pool.Run(10, threads, [&](std::size_t, int) { after.fetch_add(1); });
    EXPECT_EQ(after.load(), 10);
  }
}

// A task that makes a parallel call of its own (irrmap batch's jobs running a threaded engine) on
// the same pool finishes, even when every worker is inside an outer task.
TEST(ThreadPool, NestedRunsOnTheSamePoolFinish) {
  ThreadPool pool(3);
  constexpr std::size_t kOuter = 12, kInner = 40;
  std::vector<std::atomic<int>> inner_runs(kOuter * kInner);
  pool.Run(kOuter, 3, [&](std::size_t outer, int) {
    pool.Run(kInner, 3, [&](std::size_t inner, int) { inner_runs[outer * kInner + inner].fetch_add(1); });
  });
  for (std::size_t i = 0; i < inner_runs.size(); ++i) EXPECT_EQ(inner_runs[i].load(), 1) << "inner task " << i;
}

TEST(ThreadPool, CallsFromSeveralThreadsAtOnceEachRunTheirOwnTasks) {
  ThreadPool pool(3);
  constexpr int kCallers = 6, kCalls = 50;
  constexpr std::size_t kTasks = 37;
  std::vector<std::atomic<long>> sums(kCallers);
  std::vector<std::thread> callers;
  for (int c = 0; c < kCallers; ++c) {
    callers.emplace_back([&, c] {
      for (int call = 0; call < kCalls; ++call) {
        pool.Run(kTasks, 3, [&](std::size_t index, int) { sums[c].fetch_add(static_cast<long>(index) + 1); });
      }
    });
  }
  for (std::thread& caller : callers) caller.join();
  for (int c = 0; c < kCallers; ++c) EXPECT_EQ(sums[c].load(), kCalls * static_cast<long>(kTasks * (kTasks + 1) / 2));
}

TEST(ThreadPool, DefaultPoolHasOneThreadPerCore) {
  EXPECT_EQ(ThreadPool::Default().threads(), static_cast<int>(std::max(1u, std::thread::hardware_concurrency())));
  EXPECT_EQ(&ThreadPool::Default(), &ThreadPool::Default());
}

}  // namespace
}  // namespace vs11
