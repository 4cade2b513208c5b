// Code run in a forked worker: its result comes back whole, and a crash or an
// exception in it is an error for the caller, who goes on.
#include "keyturn/core/worker_process.h"

#include <gtest/gtest.h>

#include <csignal>
#include <cstdlib>

#include "keyturn/core/error.h"
#include "support/error_of.h"

using namespace keyturn;
using keyturn::test::errorOf;

TEST(WorkerProcess, TheResultComesBackWhole) {
  std::vector<float> big(100000);
  for (std::size_t i = 0; i < big.size(); ++i) big[i] = static_cast<float>(i) * 0.5f;
  EXPECT_EQ(inWorkerProcess([&] { return big; }, "work", "crashed", "here"), big);  // more than a pipe's buffer
  EXPECT_TRUE(inWorkerProcess([] { return std::vector<float>(); }, "work", "crashed", "here").empty());
}

TEST(WorkerProcess, ACrashIsAnErrorNamingTheSignal) {
  const std::string msg = errorOf([] { inWorkerProcess([]() -> std::vector<float> { std::abort(); }, "work", "the routine crashed", "in f"); });
  EXPECT_EQ(msg, "the routine crashed (signal " + std::to_string(SIGABRT) + ", in f)");
}

TEST(WorkerProcess, AnExceptionInTheWorkerIsAFailedWorker) {
  const std::string msg = errorOf([] {
    inWorkerProcess([]() -> std::vector<float> { throw Error("inside"); }, "work", "crashed", "here");
  });
  EXPECT_EQ(msg, "work: the worker process failed");
}
