// Configuration files: Modbus profiles, CANopen axes, pose lists, the
// simulator's configuration, camera files (keyturn's, ROS, OpenCV, Open3D; their
// distortion applied to the image corners). The first byte picks the kind.
#include "fuzz_file.h"
#include "keyturn/core/camera_file.h"
#include "keyturn/core/error.h"
#include "keyturn/core/pose_list.h"
#include "keyturn/drivers/canopen_pose.h"
#include "keyturn/drivers/modbus_profile.h"
#include "keyturn/sim/mesasr_sim_config.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const std::string text(reinterpret_cast<const char*>(data + 1), size - 1);
  try {
    switch (data[0] % 6) {
      case 0: {
        const auto p = keyturn::drivers::ModbusTurntableProfile::fromJson(text, "profile.json");
        (void)p.countsToDegrees(12345);
        break;
      }
      case 1:
        (void)keyturn::drivers::CanOpenAxis::loadAll(keyturn::fuzz::writeInput(data + 1, size - 1, "axes.json"));
        break;
      case 2:
        (void)keyturn::readPoses(keyturn::fuzz::writeInput(data + 1, size - 1, "poses.txt"));
        break;
      case 4:
      case 5: {
        const auto o = keyturn::readCameraFile(
            keyturn::fuzz::writeInput(data + 1, size - 1, data[0] % 6 == 4 ? "camera.yaml" : "camera.json"));
        if (o.intrinsics) {
          const auto& k = *o.intrinsics;
          for (const double u : {0.0, 639.0})
            (void)k.distortion.undistort({(u - k.cx) / k.fx, (479.0 - k.cy) / k.fy});
        }
        break;
      }
      default:
        (void)keyturn::sim::MesaSrSimConfig::fromFile(keyturn::fuzz::writeInput(data + 1, size - 1, "sim.json"));
    }
  } catch (const keyturn::Error&) {
  }
  return 0;
}
