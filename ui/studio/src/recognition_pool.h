#pragma once
// Live recognition off the GUI thread: a few worker threads each take the
// newest frame waiting (older ones are dropped, never queued up), run the
// recogniser on it and hand the result back to the GUI thread. With two
// workers, two frames are processed at once, so the rate is about twice what
// one thread's latency allows.
#include <QObject>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <mutex>
#include <thread>
#include <vector>

#include "frame_types.h"

namespace keyturn::studio {

class RecognitionPool : public QObject {
  Q_OBJECT
 public:
  explicit RecognitionPool(int threads, QObject* parent = nullptr);
  ~RecognitionPool() override;

  void setRecognizer(std::shared_ptr<const learning::Recognizer> r);
  std::shared_ptr<const learning::Recognizer> recognizer() const;
  void setGeodesicPaths(bool on) { paths_ = on; }
  void submit(FramePtr frame);  // GUI thread
  // A new camera run (a reconnect: its frames count from 0 again): the frame waiting is dropped and
  // the results of frames submitted before carry the older epoch, so the GUI can tell them from the
  // new camera's (a late one would set its sequence mark above every new frame's). GUI thread.
  void restart();
  std::uint64_t epoch() const;
  bool waiting() const;  // a frame is waiting for a worker
  int threads() const { return static_cast<int>(workers_.size()); }
  long dropped() const { return dropped_; }

 signals:
  void result(keyturn::studio::ViewResultPtr result);

 private:
  void work();

  mutable std::mutex mutex_;
  std::condition_variable wake_;
  FramePtr pending_;
  std::uint64_t epoch_ = 0;  // restart()s so far
  std::shared_ptr<const learning::Recognizer> recognizer_;
  std::atomic<bool> paths_{false};
  bool quit_ = false;
  std::atomic<long> dropped_{0};
  std::vector<std::thread> workers_;
};

}  // namespace keyturn::studio
