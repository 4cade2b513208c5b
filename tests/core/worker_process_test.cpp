// Code run in the worker program (keyturn-worker): its result comes back whole, a crash or a
// failure in it is an error for the caller, who goes on, and workers are kept for the next call.
#include "keyturn/core/worker_process.h"

#include <gtest/gtest.h>

#include <csignal>
#include <thread>

#include "keyturn/core/error.h"
#include "support/error_of.h"

using namespace keyturn;
using keyturn::test::errorOf;

namespace {
std::vector<float> echo(const std::vector<float>& in) { return inWorkerProcess({"echo", in}, "work", "crashed", "here"); }
}  // namespace

TEST(WorkerProcess, TheResultComesBackWhole) {
  std::vector<float> big(100000);
  for (std::size_t i = 0; i < big.size(); ++i) big[i] = static_cast<float>(i) * 0.5f;
  EXPECT_EQ(echo(big), big);  // more than a socket's buffer, both ways
  EXPECT_TRUE(echo({}).empty());
}

TEST(WorkerProcess, ACrashIsAnErrorNamingTheSignalAndTheNextCallGetsANewWorker) {
  const std::string msg = errorOf([] { inWorkerProcess({"crash", {1.f}}, "work", "the routine crashed", "in f"); });
  EXPECT_EQ(msg, "the routine crashed (signal " + std::to_string(SIGABRT) + ", in f)");
  const int before = workerProcessesStarted();
  EXPECT_EQ(echo({3.f, 4.f}), (std::vector<float>{3.f, 4.f}));
  EXPECT_EQ(workerProcessesStarted(), before + 1) << "the crashed worker is not reused";
}

TEST(WorkerProcess, AFailedJobIsAnErrorWithTheWorkersMessage) {
  EXPECT_EQ(errorOf([] { inWorkerProcess({"no-such-job", {}}, "work", "crashed", "here"); }),
            "work: unknown job 'no-such-job'");
  EXPECT_EQ(errorOf([] { inWorkerProcess({"our-cvfh", {0.01f, 1.f}}, "OUR-CVFH", "crashed", "here"); }),
            "OUR-CVFH: our-cvfh: input is not a radius and points");
}

TEST(WorkerProcess, AWorkerServesTheNextCallsAndEachConcurrentThreadHasOne) {
  echo({1.f});
  const int before = workerProcessesStarted();
  for (int i = 0; i < 5; ++i) EXPECT_EQ(echo({static_cast<float>(i)}), std::vector<float>{static_cast<float>(i)});
  EXPECT_EQ(workerProcessesStarted(), before) << "one idle worker serves calls one after another";
  // Four threads at once: each call gets a worker of its own, none is answered with another's result.
  std::vector<std::thread> threads;
  std::vector<int> wrong(4, 0);
  for (int t = 0; t < 4; ++t)
    threads.emplace_back([t, &wrong] {
      for (int i = 0; i < 50; ++i) {
        const std::vector<float> in(1000 + t, static_cast<float>(t * 1000 + i));
        wrong[t] += echo(in) != in;
      }
    });
  for (auto& th : threads) th.join();
  EXPECT_EQ(wrong, std::vector<int>(4, 0));
  EXPECT_LE(workerProcessesStarted(), before + 4);
}
