#pragma once
// Events per second over a sliding window, for the status bar.
#include <QElapsedTimer>
#include <deque>

namespace keyturn::studio {

// Events per second over the last two seconds.
class RateMeter {
 public:
  void tick() {
    const qint64 now = clock_.isValid() ? clock_.elapsed() : (clock_.start(), 0);
    times_.push_back(now);
    while (!times_.empty() && now - times_.front() > 2000) times_.pop_front();
  }
  double rate() const {
    if (times_.size() < 2) return 0;
    const qint64 span = times_.back() - times_.front();
    return span > 0 ? 1000.0 * static_cast<double>(times_.size() - 1) / static_cast<double>(span) : 0;
  }

 private:
  QElapsedTimer clock_;
  std::deque<qint64> times_;
};

}  // namespace keyturn::studio
