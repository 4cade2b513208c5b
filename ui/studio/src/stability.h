#pragma once
// How steady live recognition is: the most frequent class over the last N
// frames and the share of frames that agree with it.
#include <deque>
#include <map>

namespace keyturn::studio {

class Stability {
 public:
  explicit Stability(int window = 20) : window_(window < 1 ? 1 : window) {}
  void add(int label) {
    last_.push_back(label);
    if (static_cast<int>(last_.size()) > window_) last_.pop_front();
  }
  void clear() { last_.clear(); }
  int frames() const { return static_cast<int>(last_.size()); }
  int window() const { return window_; }
  // The most frequent label (the newest wins a tie); -1 before any frame.
  int mode() const {
    std::map<int, int> n;
    int best = -1, best_n = 0;
    for (int l : last_) ++n[l];
    for (auto it = last_.rbegin(); it != last_.rend(); ++it)
      if (n[*it] > best_n) best = *it, best_n = n[*it];
    return best;
  }
  int agreeing() const {
    const int m = mode();
    int k = 0;
    for (int l : last_) k += l == m;
    return k;
  }
  double agreement() const { return last_.empty() ? 0.0 : static_cast<double>(agreeing()) / static_cast<double>(last_.size()); }

 private:
  int window_;
  std::deque<int> last_;
};

}  // namespace keyturn::studio
