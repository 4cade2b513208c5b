// keyturn turntable: read the pose of a Modbus turntable or encoder, and move,
// home or stop a motorised one.
#include <cmath>
#include <cstdio>

#include "commands.h"
#include "keyturn/core/error.h"
#include "device_options.h"
#include "keyturn/drivers/pose_source.h"
#include "keyturn/rig/device_factory.h"

namespace keyturn::app {
namespace {

struct TurntableArgs {
  std::string pose;
  std::string profile = "keyturn-sim";
  double move_to = std::nan("");
  bool home = false, stop = false;
  double wait = 10.0;
};

int runTurntable(const TurntableArgs& a) {
  const rig::PoseSpec spec = poseSpec(a.pose, a.profile);
  if (spec.kind == rig::PoseSpec::Kind::Simulated || spec.kind == rig::PoseSpec::Kind::Playback)
    throw Error("--pose '" + a.pose + "': turntable drives a device: expected modbus-tcp:HOST:PORT, modbus-rtu:DEVICE or can:IFACE");
  rig::DeviceFactory factory;
  const auto source = factory.openPoseSource(spec);
  drivers::PoseSource& t = *source;
  const bool moving_cmd = !std::isnan(a.move_to) || a.home;
  if (!std::isnan(a.move_to)) t.moveTo(a.move_to);
  if (a.home) t.home();
  if (a.stop) t.stop();
  const drivers::Pose p = moving_cmd ? drivers::waitInPosition(t, a.wait) : t.read();
  std::printf("%.3f deg  moving=%s  in_position=%s\n", p.turntable_deg, p.moving ? "yes" : "no",
              p.in_position ? "yes" : "no");
  return 0;
}

}  // namespace

Command addTurntableCommand(CLI::App& app) {
  auto a = std::make_shared<TurntableArgs>();
  auto* cmd = app.add_subcommand("turntable", "Read, move, home or stop a Modbus turntable (or CANopen axes)");
  cmd->add_option("--pose", a->pose, "modbus-tcp:HOST:PORT[@UNIT], modbus-rtu:DEVICE[:BAUD[:8N1]][@UNIT] or can:IFACE")->required();
  cmd->add_option("--profile", a->profile, "Register map: a JSON file, generic-encoder or keyturn-sim; for can: the CANopen axes file")
      ->capture_default_str();
  cmd->add_option("--move-to", a->move_to, "Move to this angle (°) and wait until in position");
  cmd->add_flag("--home", a->home, "Move to the home position and wait");
  cmd->add_flag("--stop", a->stop, "Stop now");
  cmd->add_option("--wait", a->wait, "Longest wait for a move (s)")->capture_default_str();
  return {cmd, [a] { return runTurntable(*a); }};
}

}  // namespace keyturn::app
