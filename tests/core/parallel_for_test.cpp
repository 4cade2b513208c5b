// parallelFor: every item exactly once; an exception in one item reaches the caller
// (not std::terminate) and stops items not yet started.
#include "keyturn/core/parallel_for.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

using namespace keyturn;

TEST(ParallelFor, RunsEveryItemOnce) {
  std::vector<std::atomic<int>> count(1000);
  parallelFor(count.size(), 4, [&](std::size_t i) { ++count[i]; });
  for (std::size_t i = 0; i < count.size(); ++i) EXPECT_EQ(count[i].load(), 1) << i;
}

TEST(ParallelFor, AnExceptionInAWorkerReachesTheCallerAndStopsTheRest) {
  std::atomic<int> started{0};
  try {
    parallelFor(1000, 3, [&](std::size_t i) {
      ++started;
      if (i == 5) throw std::runtime_error("view 5 failed");
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    });
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "view 5 failed");
  }
  EXPECT_LT(started.load(), 100) << "items went on being handed out after the failure";
}
