// The studio's long jobs (Reconstruct, Enroll…) can be cancelled: the work stops at its next stage or
// step, `done` does not run, and the job reports "cancelled"; the next job starts as usual.
#include "background_job.h"

#include <gtest/gtest.h>

#include <QCoreApplication>
#include <QElapsedTimer>
#include <atomic>
#include <thread>

using keyturn::studio::BackgroundJob;

namespace {

// Runs the event loop until the job has finished (its `finished` delivered), at most 30 s.
bool waitFinished(const bool& finished) {
  QElapsedTimer t;
  t.start();
  while (!finished && t.elapsed() < 30000) QCoreApplication::processEvents(QEventLoop::AllEvents, 10);
  return finished;
}

}  // namespace

TEST(BackgroundJob, ACancelledJobStopsAtItsNextStepWithoutItsEnd) {
  int argc = 1;
  char name[] = "background_job_test";
  char* argv[] = {name, nullptr};
  QCoreApplication app(argc, argv);
  BackgroundJob job;
  bool finished = false;
  QString error;
  QObject::connect(&job, &BackgroundJob::finished, [&](const QString&, const QString& e) {
    finished = true;
    error = e;
  });
  std::atomic<int> steps{0};
  std::atomic<bool> started{false};
  bool done_ran = false;
  ASSERT_TRUE(job.start(
      "render",
      [&](BackgroundJob& j) {
        j.stage("render", 1000);
        started = true;
        for (int i = 0; i < 1000; ++i) {
          std::this_thread::sleep_for(std::chrono::milliseconds(2));
          j.step();
          ++steps;
        }
      },
      [&] { done_ran = true; }));
  while (!started) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  job.cancel();
  EXPECT_TRUE(job.cancelling());
  ASSERT_TRUE(waitFinished(finished));
  EXPECT_EQ(error, "cancelled");
  EXPECT_FALSE(done_ran);
  EXPECT_LT(steps.load(), 1000) << "stopped before its end";
  EXPECT_FALSE(job.running());

  // The next job runs to its end.
  finished = false;
  int ran = 0;
  ASSERT_TRUE(job.start(
      "again",
      [&](BackgroundJob& j) {
        j.stage("again", 3);
        for (int i = 0; i < 3; ++i) j.step(), ++ran;
      },
      [&] { done_ran = true; }));
  ASSERT_TRUE(waitFinished(finished));
  EXPECT_EQ(error, "");
  EXPECT_EQ(ran, 3);
  EXPECT_TRUE(done_ran);
  job.cancel();  // nothing running: nothing to cancel
  EXPECT_FALSE(job.cancelling());
}
