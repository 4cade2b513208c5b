#pragma once
// A progress line with ETA on stderr: redrawn in place on a terminal, printed
// every 10% otherwise (logs, CI).
#include <chrono>
#include <cstddef>
#include <mutex>
#include <string>

namespace keyturn::app {

class Progress {
 public:
  Progress(std::string label, std::size_t total, bool enabled);
  void advance(std::size_t n = 1);
  void finish();

 private:
  void draw(std::size_t done);
  std::string label_;
  std::size_t total_;
  std::size_t done_ = 0;
  bool enabled_;
  bool tty_;
  int last_decile_ = -1;
  std::chrono::steady_clock::time_point start_;
  std::mutex mutex_;
};

std::string formatDuration(double seconds);

}  // namespace keyturn::app
