#include "studio_rig_factory.h"

#include <stdlib.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "camera_choice.h"
#include "keyturn/core/error.h"
#include "keyturn/drivers/modbus_turntable.h"
#include "keyturn/sim/mesasr_sim_config.h"
#include "keyturn/sim/mesh.h"
#include "keyturn/sim/tof_view.h"
#include "keyturn/sim/turntable_sim.h"
#include "pose_choice.h"

namespace fs = std::filesystem;

namespace keyturn::app {
namespace {

// The SR4000's frame rate at its default settings (MESA: up to 54 frames/s).
constexpr double kSimFrameRate = 50.0;

// The simulated turntable: its Modbus server in this process and the real
// Modbus driver talking to it over loopback.
class SimulatedTurntable final : public drivers::PoseSource {
 public:
  SimulatedTurntable(const std::string& world, drivers::ModbusOptions mo) {
    sim::TurntableServerOptions so;
    so.world_file = world;
    server_ = std::make_unique<sim::TurntableServer>(so);
    client_ = std::make_unique<drivers::ModbusTurntable>(drivers::ModbusEndpoint::parse(server_->endpoint()),
                                                         drivers::ModbusTurntableProfile::load("keyturn-sim"), mo);
  }
  ~SimulatedTurntable() override {
    client_.reset();  // the client goes first: it talks to the server
  }
  drivers::Pose read() override { return client_->read(); }
  bool canMove() const override { return true; }
  void moveTo(double deg) override { client_->moveTo(deg); }
  void home() override { client_->home(); }
  void stop() override { client_->stop(); }
  std::string describe() const override { return "simulated turntable, " + client_->describe(); }

 private:
  std::unique_ptr<sim::TurntableServer> server_;
  std::unique_ptr<drivers::ModbusTurntable> client_;
};

}  // namespace

StudioRigFactory::StudioRigFactory(std::string objects_csv) {
  try {
    for (const auto& o : readObjectList(objects_csv)) objects_.push_back({o.cls, o.instance, o.mesh});
  } catch (const Error&) {
    // Without the object list the simulated camera still has its built-in mug.
  }
  if (objects_.empty()) objects_.push_back({"mug", "builtin", "builtin:mug"});
  dir_ = (fs::temp_directory_path() / ("keyturn-studio-" + std::to_string(::getpid()))).string();
  fs::create_directories(dir_);
  // libmesasr-sim reads its configuration from the environment at every open: set it once here,
  // before any device thread runs, rather than from the camera thread (setenv is not thread-safe).
  ::setenv("MESASR_SIM_CONFIG", (dir_ + "/camera.json").c_str(), 1);
}

StudioRigFactory::~StudioRigFactory() {
  std::error_code ec;
  fs::remove_all(dir_, ec);
}

std::unique_ptr<drivers::TofCamera> StudioRigFactory::openCamera(const studio::CameraRequest& r, Log log) {
  using Kind = studio::CameraRequest::Kind;
  if (r.kind != Kind::Simulated) {
    std::lock_guard<std::mutex> l(mutex_);
    camera_from_turntable_.reset();  // a real rig: not calibrated from here
  }
  if (r.kind == Kind::Usb)
    return app::openCamera(r.usb_serial ? "usb:" + std::to_string(r.usb_serial) : "usb", "", "", log);
  if (r.kind == Kind::Ethernet) return app::openCamera("eth:" + r.address, "", "", log);
  const studio::SimObject* object = &objects_.front();
  for (const auto& o : objects_)
    if (o.instance == r.sim_object) object = &o;
  sim::MesaSrSimConfig c;
  c.mesh = object->mesh;
  c.elevation = r.sim_elevation_deg;
  c.distance = r.sim_distance_m;
  c.world = dir_ + "/world.json";
  c.unplug_file = dir_ + "/unplugged";
  c.frame_rate = kSimFrameRate;
  c.save(dir_ + "/camera.json");  // $MESASR_SIM_CONFIG (set in the constructor)
  sim::SceneView view;
  view.distance = r.sim_distance_m;
  view.elevation_deg = r.sim_elevation_deg;
  const Eigen::Matrix4d pose = sim::cameraFromTurntable(sim::loadMeshOrBuiltin(c.mesh), view);
  {
    std::lock_guard<std::mutex> l(mutex_);
    camera_from_turntable_ = pose;
  }
  return app::openCamera("sim", "", "", log);
}

std::unique_ptr<drivers::PoseSource> StudioRigFactory::openPose(const studio::PoseRequest& r, Log log) {
  using Kind = studio::PoseRequest::Kind;
  drivers::ModbusOptions mo;
  mo.log = log;
  switch (r.kind) {
    case Kind::Simulated: return std::make_unique<SimulatedTurntable>(dir_ + "/world.json", mo);
    case Kind::ModbusTcp: return openPoseSource("modbus-tcp:" + r.endpoint, r.profile).source;
    case Kind::ModbusRtu: return openPoseSource("modbus-rtu:" + r.endpoint, r.profile).source;
    case Kind::Can: return openPoseSource("can:" + r.endpoint, r.profile).source;
    case Kind::None: break;
  }
  throw Error("no pose source chosen");
}

void StudioRigFactory::setSimulatedCameraUnplugged(bool unplugged) {
  const std::string flag = dir_ + "/unplugged";
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

}  // namespace keyturn::app
