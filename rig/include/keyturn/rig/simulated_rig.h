#pragma once
// The simulated rig, for the CLI and the studio alike: the simulated SR4000
// (libmesasr-sim, opened through the real driver) or the simulated Kinect-class
// camera (the simulated OpenNI2 driver, opened through the real libOpenNI2) and the simulated turntable
// (its Modbus server in this process and the real Modbus driver talking to it
// over loopback), sharing one world file in the rig's folder. Both are opened by
// the device factory (device_factory.h); this file writes what they share.
#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <string>

#include "keyturn/drivers/pose_source.h"
#include "keyturn/drivers/tof_camera.h"
#include "keyturn/rig/device_factory.h"
#include "keyturn/rig/device_spec.h"
#include "keyturn/sim/turntable_sim.h"

namespace keyturn::drivers {
class ModbusTurntable;
}

namespace keyturn::rig {

// The rig's files: DIR/world.json (the shared world), DIR/camera.json (libmesasr-sim's configuration).
struct SimulatedRigFiles {
  std::string dir;
  std::string world() const { return dir + "/world.json"; }
  std::string cameraConfig() const { return dir + "/camera.json"; }
};

struct SimulatedCameraOptions {
  std::string mesh = "builtin:mug";  // builtin:NAME or a mesh file
  double elevation_deg = 30;
  double distance = 0;               // 0: the mesh's own framing distance
  double roll_deg = 0;               // about the optical axis: a camera mounted off level
  double scale = 1;                  // the mesh grown by this factor (another instance's size)
  std::uint64_t seed = 1;
  double fault_rate = 0;             // random faults per acquisition
  double frame_rate = 0;             // 0: as fast as it renders
  bool noise_per_pose = false;       // the noise fixed per pose, both cameras (MesaSrSimConfig)
  std::string world;                 // the world file to follow; empty: a still turntable
  std::string unplug_file;           // while this file exists the camera is unplugged
};

// Writes libmesasr-sim's configuration for this object and elevation to path (its folder made) and
// returns the spec that opens it: sim:PATH. Mesh and world paths are written absolute.
CameraSpec writeSimulatedCameraConfig(const std::string& path, const SimulatedCameraOptions& o);

// The simulated turntable as one PoseSource: it owns its server, which outlives the driver.
class SimulatedTurntable final : public drivers::PoseSource {
 public:
  SimulatedTurntable(sim::TurntableServerOptions server, DeviceLog log = {});
  ~SimulatedTurntable() override;
  drivers::Pose read() override;
  bool canMove() const override { return true; }
  void moveTo(double deg) override;
  void home() override;
  void stop() override;
  std::string describe() const override;
  const sim::TurntableServer& server() const { return *server_; }

 private:
  std::unique_ptr<sim::TurntableServer> server_;
  std::unique_ptr<drivers::ModbusTurntable> client_;
};

// Motion of a simulated table for captures: real time ×12, or (fast) without settling.
sim::TurntableMotion captureMotion(bool fast);

struct SimulatedRigOptions {
  std::string dir;                   // the rig's files (e.g. DATASET/.sim)
  SimulatedCameraOptions camera;     // its world is the rig's own unless world is given
  bool simulated_pose = true;        // false: the camera is simulated, the pose source real
  std::string world;                 // with a separately running simulated turntable: its --world file
  bool fast = false;                 // shrink motion and settling far below real time
  bool openni2 = false;              // the camera seen through the simulated OpenNI2 driver (a Kinect-class
                                     // camera, openni2:keyturn-sim://CONFIG) instead of libmesasr-sim
};

// The URI under which the simulated OpenNI2 driver opens the simulated camera's configuration file.
std::string simulatedOpenNi2Uri(const std::string& config_path);

struct SimulatedRig {
  std::unique_ptr<drivers::TofCamera> camera;
  std::unique_ptr<SimulatedTurntable> turntable;  // when simulated_pose
  Eigen::Matrix4d camera_from_turntable = Eigen::Matrix4d::Identity();  // exact, at 0°
};

SimulatedRig openSimulatedRig(const SimulatedRigOptions& o);

}  // namespace keyturn::rig
