#pragma once
// Where the object is: a turntable angle, or a Cartesian robot's position.
// Motion commands are optional (an encoder only reports).
#include <Eigen/Core>
#include <chrono>
#include <cmath>
#include <string>

namespace keyturn::drivers {

struct Pose {
  double turntable_deg = std::nan("");      // NaN when the source has no turntable
  Eigen::Vector3d position = Eigen::Vector3d::Constant(std::nan(""));  // metres (robot)
  bool moving = false;
  bool in_position = true;
  std::chrono::system_clock::time_point stamp;
};

class PoseSource {
 public:
  virtual ~PoseSource() = default;
  virtual Pose read() = 0;  // throws keyturn::Error naming the device on failure
  virtual bool canMove() const { return false; }
  virtual void moveTo(double /*turntable_deg*/) { unsupported("move"); }
  virtual void home() { unsupported("home"); }
  virtual void stop() { unsupported("stop"); }
  virtual std::string describe() const = 0;

 protected:
  [[noreturn]] void unsupported(const char* what) const;
};

// After a move command: reads the pose until it is in position (every 20 ms, after a first 20 ms
// for the command to land). Throws keyturn::Error naming the device, the wait and the angle
// when it is not in position within timeout_s.
Pose waitInPosition(PoseSource& pose, double timeout_s);

}  // namespace keyturn::drivers
