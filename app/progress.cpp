#include "progress.h"

#include <unistd.h>

#include <cstdio>

namespace keyturn::app {

std::string formatDuration(double seconds) {
  if (seconds < 0) seconds = 0;
  const long s = static_cast<long>(seconds + 0.5);
  char buf[32];
  if (s >= 3600) std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld", s / 3600, (s / 60) % 60, s % 60);
  else std::snprintf(buf, sizeof buf, "%02ld:%02ld", s / 60, s % 60);
  return buf;
}

Progress::Progress(std::string label, std::size_t total, bool enabled)
    : label_(std::move(label)), total_(total), enabled_(enabled && total > 0),
      tty_(::isatty(STDERR_FILENO) != 0), start_(std::chrono::steady_clock::now()) {}

void Progress::advance(std::size_t n) {
  std::lock_guard<std::mutex> lock(mutex_);
  done_ += n;
  draw(done_);
}

void Progress::draw(std::size_t done) {
  if (!enabled_) return;
  const double frac = static_cast<double>(done) / static_cast<double>(total_);
  const int decile = static_cast<int>(frac * 10);
  if (!tty_ && decile == last_decile_ && done != total_) return;
  last_decile_ = decile;
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double eta = done > 0 ? elapsed / static_cast<double>(done) * static_cast<double>(total_ - done) : 0;
  const int width = 30, filled = static_cast<int>(frac * width);
  std::string bar(static_cast<std::size_t>(filled), '#');
  bar.resize(width, '.');
  std::fprintf(stderr, "%s%s [%s] %zu/%zu %3.0f%% elapsed %s ETA %s%s", tty_ ? "\r" : "",
               label_.c_str(), bar.c_str(), done, total_, frac * 100.0, formatDuration(elapsed).c_str(),
               formatDuration(eta).c_str(), tty_ ? "" : "\n");
  std::fflush(stderr);
}

void Progress::finish() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (enabled_ && tty_) std::fprintf(stderr, "\n");
  enabled_ = false;
}

}  // namespace keyturn::app
