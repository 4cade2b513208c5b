// The studio's recognition pool across a camera reconnect: a result of the camera before it carries
// the older epoch, so the live view does not let its frame count stand for the new camera's (issue 51:
// a late result of the previous camera held back every result of the new one until the new camera's
// frames counted past it).
#include "recognition_pool.h"

#include <gtest/gtest.h>

#include <QCoreApplication>
#include <QElapsedTimer>
#include <thread>

using keyturn::studio::FramePtr;
using keyturn::studio::RecognitionPool;
using keyturn::studio::ViewResultPtr;

namespace {

FramePtr frame(std::uint64_t sequence) {
  auto f = std::make_shared<keyturn::drivers::TofFrame>();
  f->sequence = sequence;
  f->timestamp = std::chrono::system_clock::now();
  return f;
}

}  // namespace

TEST(RecognitionPool, AResultOfTheCameraBeforeARestartCarriesTheOlderEpoch) {
  int argc = 1;
  char name[] = "recognition_pool_test";
  char* argv[] = {name, nullptr};
  QCoreApplication app(argc, argv);
  RecognitionPool pool(1);  // no recogniser: each result is "no recogniser", made at once
  std::vector<ViewResultPtr> results;
  QObject::connect(&pool, &RecognitionPool::result, [&](ViewResultPtr r) { results.push_back(r); });

  // The old camera's frame 900, taken by the worker; its result waits in the event queue (the GUI
  // thread is busy) while the camera reconnects.
  pool.submit(frame(900));
  QElapsedTimer t;
  t.start();
  while (pool.waiting() && t.elapsed() < 10000) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  ASSERT_FALSE(pool.waiting()) << "the worker never took the frame";
  const std::uint64_t before = pool.epoch();
  pool.restart();
  EXPECT_EQ(pool.epoch(), before + 1);
  pool.submit(frame(0));  // the new camera's first frame
  while (results.size() < 2 && t.elapsed() < 10000) QCoreApplication::processEvents(QEventLoop::AllEvents, 10);
  ASSERT_EQ(results.size(), 2u);
  EXPECT_EQ(results[0]->frame->sequence, 900u);
  EXPECT_EQ(results[0]->epoch, before) << "the old camera's result is told apart";
  EXPECT_EQ(results[1]->frame->sequence, 0u);
  EXPECT_EQ(results[1]->epoch, pool.epoch());
}
