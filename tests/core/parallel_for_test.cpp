// parallelFor: every item exactly once; an exception in one item reaches the caller
// (not std::terminate) and stops items not yet started.
#include "keyturn/core/parallel_for.h"

#include <gtest/gtest.h>

#include <atomic>
#include <condition_variable>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

using namespace keyturn;

TEST(ParallelFor, RunsEveryItemOnce) {
  std::vector<std::atomic<int>> count(1000);
  parallelFor(count.size(), 4, [&](std::size_t i) { ++count[i]; });
  for (std::size_t i = 0; i < count.size(); ++i) EXPECT_EQ(count[i].load(), 1) << i;
}

// Two threads: the worker thread fails its first item; the caller's thread holds its own item until the
// worker thread has ended (so the failure is recorded), then must find no item left to start. No sleep:
// the order is forced, so at most one item starts per thread on any machine (the caller's none when the
// worker thread failed before the caller took an item).
namespace {
struct ThreadEnd {  // signals when the thread that made it ends
  std::mutex& mutex;
  std::condition_variable& ended;
  bool& flag;
  ~ThreadEnd() {
    {
      const std::lock_guard<std::mutex> l(mutex);
      flag = true;
    }
    ended.notify_all();
  }
};
}  // namespace

TEST(ParallelFor, AnExceptionInAWorkerReachesTheCallerAndStopsTheRest) {
  const std::thread::id caller = std::this_thread::get_id();
  std::atomic<int> started{0};
  std::mutex mutex;
  std::condition_variable ended;
  bool worker_ended = false;
  try {
    parallelFor(1000, 2, [&](std::size_t i) {
      ++started;
      if (std::this_thread::get_id() != caller) {
        thread_local ThreadEnd end{mutex, ended, worker_ended};
        (void)end;
        throw std::runtime_error("view " + std::to_string(i) + " failed");
      }
      std::unique_lock<std::mutex> l(mutex);
      ended.wait(l, [&] { return worker_ended; });
    });
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_TRUE(std::string(e.what()) == "view 0 failed" || std::string(e.what()) == "view 1 failed") << e.what();
  }
  EXPECT_LE(started.load(), 2) << "items went on being handed out after the failure";
}
