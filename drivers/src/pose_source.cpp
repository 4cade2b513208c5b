#include "keyturn/drivers/pose_source.h"

#include <chrono>
#include <thread>

#include "keyturn/core/error.h"

namespace keyturn::drivers {

void PoseSource::unsupported(const char* what) const {
  throw Error(describe() + ": cannot " + std::string(what) + " (a read-only pose source)");
}

Pose waitInPosition(PoseSource& pose, double timeout_s) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  Pose p;
  for (p = pose.read(); !p.in_position && std::chrono::steady_clock::now() < end; p = pose.read())
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  if (!p.in_position)
    throw Error(pose.describe() + ": not in position after " + std::to_string(timeout_s) + " s (at " +
                std::to_string(p.turntable_deg) + "°)");
  return p;
}

}  // namespace keyturn::drivers
