#pragma once
// The simulated rig for one object at one camera elevation: the simulated
// turntable (in this process, over loopback Modbus) and the simulated SR4000
// (libmesasr-sim) sharing one world file under DATASET/.sim/, opened through
// the real drivers.
#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>

#include "keyturn/drivers/tof_camera.h"
#include "pose_choice.h"

namespace keyturn::app {

struct SimRigOptions {
  std::string dataset_root;
  std::string mesh = "builtin:mug";
  double elevation_deg = 30;
  double distance = 0;
  std::uint64_t seed = 1;
  bool simulated_pose = true;   // false: the camera is simulated, the pose source real
  std::string world;            // with a separately running simulated turntable: its --world file
  bool fast = false;            // shrink motion and settling far below real time
  double fault_rate = 0;        // random faults per camera acquisition and per turntable request
};

struct SimRig {
  PoseChoice pose;                          // set when simulated_pose
  std::unique_ptr<drivers::TofCamera> camera;
  Eigen::Matrix4d camera_from_turntable;    // exact, at 0°
};

// Configures libmesasr-sim for this object and elevation and opens the camera;
// starts the simulated turntable when asked.
SimRig openSimRig(const SimRigOptions& o);

}  // namespace keyturn::app
