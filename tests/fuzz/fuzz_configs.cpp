// Configuration files: Modbus profiles, CANopen axes, pose lists, the
// simulator's configuration. The first byte picks the kind.
#include "fuzz_file.h"
#include "keyturn/core/error.h"
#include "keyturn/core/pose_list.h"
#include "keyturn/drivers/canopen_pose.h"
#include "keyturn/drivers/modbus_profile.h"
#include "keyturn/sim/mesasr_sim_config.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const std::string text(reinterpret_cast<const char*>(data + 1), size - 1);
  try {
    switch (data[0] % 4) {
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
      default:
        (void)keyturn::sim::MesaSrSimConfig::fromFile(keyturn::fuzz::writeInput(data + 1, size - 1, "sim.json"));
    }
  } catch (const keyturn::Error&) {
  }
  return 0;
}
