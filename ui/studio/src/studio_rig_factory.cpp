#include "keyturn/studio/studio_rig_factory.h"

#include <filesystem>
#include <fstream>

#include "keyturn/core/error.h"
#include "keyturn/dataset/object_list.h"
#include "keyturn/drivers/openni2_camera.h"

namespace fs = std::filesystem;

namespace keyturn::studio {
namespace {

// The SR4000's frame rate at its default settings (MESA: up to 54 frames/s).
constexpr double kSimFrameRate = 50.0;
// A Kinect-class camera's depth stream.
constexpr double kSimOpenNi2FrameRate = 30.0;

}  // namespace

StudioRigFactory::StudioRigFactory(std::string objects_csv, bool noise_per_pose) : noise_per_pose_(noise_per_pose) {
  try {
    for (const auto& o : dataset::readObjectList(objects_csv)) objects_.push_back({o.cls, o.instance, o.mesh});
  } catch (const Error&) {
    // Without the object list the simulated camera still has its built-in mug.
  }
  if (objects_.empty()) objects_.push_back({"mug", "builtin", "builtin:mug"});
  files_.dir = folder_.path();
  sim::TurntableServerOptions table;  // the table's real-time motion
  table.world_file = files_.world();
  devices_ = std::make_unique<rig::DeviceFactory>(table);
}

StudioRigFactory::~StudioRigFactory() = default;  // the devices close before folder_ goes

std::unique_ptr<drivers::TofCamera> StudioRigFactory::openCamera(const rig::CameraSpec& spec, Log log) {
  return devices_->openCamera(spec, std::move(log));
}

std::unique_ptr<drivers::PoseSource> StudioRigFactory::openPose(const rig::PoseSpec& spec, Log log) {
  return devices_->openPoseSource(spec, std::move(log));
}

namespace {

rig::SimulatedCameraOptions simulatedCameraOptions(const std::vector<SimObject>& objects, const std::string& sim_object,
                                                   const rig::SimulatedRigFiles& files, double frame_rate,
                                                   bool noise_per_pose) {
  const SimObject* object = &objects.front();
  for (const auto& o : objects)
    if (o.instance == sim_object) object = &o;
  rig::SimulatedCameraOptions c;
  c.mesh = object->mesh;
  c.world = files.world();
  c.unplug_file = files.dir + "/unplugged";
  c.frame_rate = frame_rate;
  c.noise_per_pose = noise_per_pose;
  return c;
}

}  // namespace

rig::CameraSpec StudioRigFactory::simulatedCamera(const std::string& sim_object) {
  const rig::SimulatedCameraOptions c = simulatedCameraOptions(objects_, sim_object, files_, kSimFrameRate, noise_per_pose_);
  std::lock_guard<std::mutex> l(config_mutex_);
  return rig::writeSimulatedCameraConfig(files_.cameraConfig(), c);
}

// The simulated OpenNI2 driver reads the SR4000 simulator's configuration file (a URI naming it is a
// device: simulators/openni2_sim/sim_uri.h), so the same file puts it on the studio's rig. Before,
// the default device showed its own built-in mug, which no model of the studio was trained on
// ("unknown 0.32 < 0.40" beside 99.9 % for the YCB mug, issue 47).
rig::CameraSpec StudioRigFactory::simulatedOpenNi2Camera(const std::string& sim_object) {
  const rig::SimulatedCameraOptions c = simulatedCameraOptions(objects_, sim_object, files_, kSimOpenNi2FrameRate, noise_per_pose_);
  std::lock_guard<std::mutex> l(config_mutex_);
  const rig::CameraSpec written = rig::writeSimulatedCameraConfig(files_.cameraConfig(), c);
  return rig::openNi2CameraSpec("keyturn-sim://" + fs::absolute(written.sim_config).string());
}

void StudioRigFactory::setSimulatedCameraUnplugged(bool unplugged) {
  const std::string flag = files_.dir + "/unplugged";
  if (unplugged) std::ofstream(flag) << "pulled in keyturn studio\n";
  else fs::remove(flag);
}

std::vector<rig::FoundCamera> StudioRigFactory::usbCameras() { return rig::findUsbCameras(); }

std::vector<rig::FoundCamera> StudioRigFactory::openni2Cameras() { return rig::findOpenNi2Cameras(); }

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

std::optional<Eigen::Matrix4d> StudioRigFactory::cameraFromTurntable() const { return devices_->cameraFromTurntable(); }

}  // namespace keyturn::studio
