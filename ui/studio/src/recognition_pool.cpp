#include "recognition_pool.h"

#include <chrono>

#include "keyturn/core/empty_view.h"

namespace keyturn::studio {

RecognitionPool::RecognitionPool(int threads, QObject* parent) : QObject(parent) {
  for (int i = 0; i < std::max(1, threads); ++i) workers_.emplace_back([this] { work(); });
}

RecognitionPool::~RecognitionPool() {
  {
    std::lock_guard<std::mutex> l(mutex_);
    quit_ = true;
  }
  wake_.notify_all();
  for (auto& t : workers_) t.join();
}

void RecognitionPool::setRecognizer(std::shared_ptr<const learning::Recognizer> r) {
  std::lock_guard<std::mutex> l(mutex_);
  recognizer_ = std::move(r);
}

std::shared_ptr<const learning::Recognizer> RecognitionPool::recognizer() const {
  std::lock_guard<std::mutex> l(mutex_);
  return recognizer_;
}

void RecognitionPool::submit(FramePtr frame) {
  {
    std::lock_guard<std::mutex> l(mutex_);
    if (pending_) ++dropped_;  // no worker took the last one: the newer frame replaces it
    pending_ = std::move(frame);
  }
  wake_.notify_one();
}

void RecognitionPool::restart() {
  std::lock_guard<std::mutex> l(mutex_);
  pending_.reset();
  ++epoch_;
}

std::uint64_t RecognitionPool::epoch() const {
  std::lock_guard<std::mutex> l(mutex_);
  return epoch_;
}

bool RecognitionPool::waiting() const {
  std::lock_guard<std::mutex> l(mutex_);
  return pending_ != nullptr;
}

void RecognitionPool::work() {
  for (;;) {
    FramePtr frame;
    std::shared_ptr<const learning::Recognizer> rec;
    std::uint64_t epoch = 0;
    {
      std::unique_lock<std::mutex> l(mutex_);
      wake_.wait(l, [&] { return quit_ || pending_; });
      if (quit_) return;
      frame = std::move(pending_);
      pending_.reset();
      rec = recognizer_;
      epoch = epoch_;
    }
    auto out = std::make_shared<ViewResult>();
    out->frame = frame;
    out->epoch = epoch;
    out->recognizer = rec;
    if (!rec) {
      out->error = "no recogniser";
    } else {
      try {
        // The descriptor hands back the paths on the graph it built (no second build).
        auto r = std::make_shared<learning::Recognition>(rec->recognize(frame->cloud, paths_));
        out->geodesic_paths = std::move(r->descriptor.geodesic_paths);
        out->recognition = std::move(r);
      } catch (const EmptyViewError& e) {
        out->error = e.what();
        out->no_object = true;
      } catch (const std::exception& e) {
        out->error = e.what();
      }
    }
    out->latency_ms =
        std::chrono::duration<double, std::milli>(std::chrono::system_clock::now() - frame->timestamp).count();
    ViewResultPtr done = out;
    QMetaObject::invokeMethod(this, [this, done] { emit result(done); }, Qt::QueuedConnection);
  }
}

}  // namespace keyturn::studio
