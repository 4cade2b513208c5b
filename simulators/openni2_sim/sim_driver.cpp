// The simulated OpenNI2 driver (libKeyturnSimOpenNI2.so.0): an OpenNI2 driver
// plugin, built against Debian's OniDriverAPI.h and loaded by the real
// libOpenNI2 from a drivers folder, that serves the simulated rig as a
// Kinect-class depth camera. sim_uri.h names its devices.
#include <cstdio>
#include <list>
#include <set>
#include <string>

#include "keyturn/core/error.h"
#include "sim_device.h"
#include "sim_uri.h"

namespace keyturn::sim::openni2 {

struct FrameSyncGroup {
  int streams;
};

class SimDriver : public oni::driver::DriverBase {
 public:
  explicit SimDriver(OniDriverServices* services) : DriverBase(services) {}

  OniStatus initialize(oni::driver::DeviceConnectedCallback connected,
                       oni::driver::DeviceDisconnectedCallback disconnected,
                       oni::driver::DeviceStateChangedCallback state_changed, void* cookie) override {
    DriverBase::initialize(connected, disconnected, state_changed, cookie);
    announce(kDefaultUri);  // one device is always there, as one camera plugged in
    return ONI_STATUS_OK;
  }

  // OpenNI asks every driver about a URI it has not seen: a keyturn-sim:// URI
  // naming a configuration file becomes a device.
  OniStatus tryDevice(const char* uri) override {
    const auto path = configPathOf(uri ? uri : "");
    if (!path) return ONI_STATUS_ERROR;
    try {
      load(*path);
    } catch (const std::exception& e) {
      getServices().errorLoggerAppend("%s", e.what());
      return ONI_STATUS_ERROR;
    }
    announce(uri);
    return ONI_STATUS_OK;
  }

  oni::driver::DeviceBase* deviceOpen(const char* uri, const char* /*mode*/) override {
    const auto path = configPathOf(uri ? uri : "");
    if (!path) return nullptr;
    try {
      const MesaSrSimConfig config = load(*path);
      if (config.faults.open_fail) throw Error(std::string(uri) + ": simulated open failure (faults.open_fail)");
      if (unplugged(config))
        throw Error(std::string(uri) + ": unplugged (" + config.unplug_file + " exists)");
      return new SimDevice(config, scenes_);
    } catch (const std::exception& e) {
      getServices().errorLoggerAppend("%s", e.what());
      return nullptr;
    }
  }

  void deviceClose(oni::driver::DeviceBase* device) override { delete static_cast<SimDevice*>(device); }

  void shutdown() override {}

  // libOpenNI2 pairs synced depth and colour frames by frame index itself; the
  // device already gives the frames of one instant one index, so a sync group
  // needs nothing from the driver but a handle.
  void* enableFrameSync(oni::driver::StreamBase** /*streams*/, int count) override {
    return count > 0 ? new FrameSyncGroup{count} : nullptr;
  }
  void disableFrameSync(void* group) override { delete static_cast<FrameSyncGroup*>(group); }

 private:
  static MesaSrSimConfig load(const std::string& path) {
    return path.empty() ? MesaSrSimConfig::fromEnvironment(kConfigVariable) : MesaSrSimConfig::fromFile(path);
  }

  void announce(const std::string& uri) {
    if (!announced_.insert(uri).second) return;
    OniDeviceInfo info{};
    std::snprintf(info.uri, sizeof info.uri, "%s", uri.c_str());
    std::snprintf(info.vendor, sizeof info.vendor, "keyturn");
    std::snprintf(info.name, sizeof info.name, "Simulated structured-light camera");
    infos_.push_back(info);  // a list: the address OpenNI is given stays valid
    deviceConnected(&infos_.back());
  }

  std::set<std::string> announced_;
  std::list<OniDeviceInfo> infos_;
  // Scenes kept between opens: a reopened or replugged device's first frame needs no new cast.
  StructuredLightScenes scenes_;
};

}  // namespace keyturn::sim::openni2

ONI_EXPORT_DRIVER(keyturn::sim::openni2::SimDriver)
