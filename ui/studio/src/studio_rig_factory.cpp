#include "keyturn/studio/studio_rig_factory.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "keyturn/core/error.h"
#include "keyturn/rig/devices.h"
#include "keyturn/dataset/object_list.h"

namespace fs = std::filesystem;

namespace keyturn::studio {
namespace {

// The SR4000's frame rate at its default settings (MESA: up to 54 frames/s).
constexpr double kSimFrameRate = 50.0;

}  // namespace

StudioRigFactory::StudioRigFactory(std::string objects_csv) {
  try {
    for (const auto& o : dataset::readObjectList(objects_csv)) objects_.push_back({o.cls, o.instance, o.mesh});
  } catch (const Error&) {
    // Without the object list the simulated camera still has its built-in mug.
  }
  if (objects_.empty()) objects_.push_back({"mug", "builtin", "builtin:mug"});
  files_.dir = (fs::temp_directory_path() / ("keyturn-studio-" + std::to_string(::getpid()))).string();
  fs::create_directories(files_.dir);
  // Before any device thread runs (setenv is not thread-safe).
  rig::useSimulatedCameraConfig(files_);
}

StudioRigFactory::~StudioRigFactory() {
  std::error_code ec;
  fs::remove_all(files_.dir, ec);
}

std::unique_ptr<drivers::TofCamera> StudioRigFactory::openCamera(const CameraRequest& r, Log log) {
  using Kind = CameraRequest::Kind;
  if (r.kind != Kind::Simulated) {
    std::lock_guard<std::mutex> l(mutex_);
    camera_from_turntable_.reset();  // a real rig: not calibrated from here
  }
  if (r.kind == Kind::Usb)
    return rig::openCamera(r.usb_serial ? "usb:" + std::to_string(r.usb_serial) : "usb", "", "", log);
  if (r.kind == Kind::Ethernet) return rig::openCamera("eth:" + r.address, "", "", log);
  if (r.kind == Kind::Playback) {
    auto played = recording(r.playback);
    if (played->ended()) played->rewind();  // Connect after the end plays it again (the pose follows: same timeline)
    std::lock_guard<std::mutex> l(mutex_);
    camera_from_turntable_ = played->cameraFromTurntable();  // the recorded calibration, for captures from it
    return std::make_unique<rig::PlaybackCamera>(played);
  }
  const SimObject* object = &objects_.front();
  for (const auto& o : objects_)
    if (o.instance == r.sim_object) object = &o;
  rig::SimulatedCameraOptions c;
  c.mesh = object->mesh;
  c.elevation_deg = r.sim_elevation_deg;
  c.distance = r.sim_distance_m;
  c.world = files_.world();
  c.unplug_file = files_.dir + "/unplugged";
  c.frame_rate = kSimFrameRate;
  Eigen::Matrix4d pose;
  auto camera = rig::openSimulatedCamera(files_, c, &pose, log);
  std::lock_guard<std::mutex> l(mutex_);
  camera_from_turntable_ = pose;
  return camera;
}

std::unique_ptr<drivers::PoseSource> StudioRigFactory::openPose(const PoseRequest& r, Log log) {
  using Kind = PoseRequest::Kind;
  switch (r.kind) {
    case Kind::Simulated: {
      sim::TurntableServerOptions so;  // the table's real-time motion
      so.world_file = files_.world();
      return std::make_unique<rig::SimulatedTurntable>(so, log);
    }
    case Kind::ModbusTcp: return rig::openPoseSource("modbus-tcp:" + r.endpoint, r.profile, log);
    case Kind::ModbusRtu: return rig::openPoseSource("modbus-rtu:" + r.endpoint, r.profile, log);
    case Kind::Can: return rig::openPoseSource("can:" + r.endpoint, r.profile, log);
    case Kind::Playback: return std::make_unique<rig::PlaybackPose>(recording(r.playback));
    case Kind::None: break;
  }
  throw Error("no pose source chosen");
}

std::shared_ptr<rig::Recording> StudioRigFactory::recording(const PlaybackRequest& r) {
  std::lock_guard<std::mutex> l(mutex_);
  if (!recording_ || !(playing_ == r)) {
    recording_ = std::make_shared<rig::Recording>(r.dataset, rig::PlaybackOptions{r.rate_fps, r.loop});
    playing_ = r;
  }
  return recording_;
}

void StudioRigFactory::setSimulatedCameraUnplugged(bool unplugged) {
  const std::string flag = files_.dir + "/unplugged";
  if (unplugged) std::ofstream(flag) << "pulled in keyturn studio\n";
  else fs::remove(flag);
}

std::vector<std::pair<unsigned, std::string>> StudioRigFactory::usbCameras() {
  std::vector<std::pair<unsigned, std::string>> out;
  for (const auto& c : drivers::listSwissRangerCameras()) {
    unsigned serial = 0;
    try {
      serial = static_cast<unsigned>(std::stoul(c.serial));
    } catch (const std::exception&) {
    }
    std::string text = c.model + (c.serial.empty() ? "" : " " + c.serial) + " on USB " + c.port_path;
    if (!c.accessible) text += " (no access: " + c.access_error + ")";
    out.emplace_back(serial, text);
  }
  return out;
}

bool StudioRigFactory::usbCamerasChanged() {
  if (!hotplug_tried_) {
    hotplug_tried_ = true;
    try {
      hotplug_ = std::make_unique<drivers::UsbHotplugWatcher>(
          [this](bool, const drivers::UsbCameraInfo&) { usb_changed_ = true; });
    } catch (const Error&) {
      // No hot-plug here (or no USB at all): the panel's Rescan still works.
    }
  }
  if (!hotplug_) return false;
  hotplug_->poll(0);
  const bool changed = usb_changed_;
  usb_changed_ = false;
  return changed;
}

std::optional<Eigen::Matrix4d> StudioRigFactory::cameraFromTurntable() const {
  std::lock_guard<std::mutex> l(mutex_);
  return camera_from_turntable_;
}

}  // namespace keyturn::studio
