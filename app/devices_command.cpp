// keyturn devices: SwissRanger cameras on USB, whether this user may open
// them, and the udev rule when not; then the OpenNI2 depth cameras (Kinect,
// Xtion, Astra) with their URIs, depth modes and intrinsics. --watch follows
// the SwissRangers' hot-plug events.
#include <csignal>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <thread>

#include "commands.h"
#include "keyturn/core/error.h"
#include "keyturn/drivers/openni2_camera.h"
#include "keyturn/drivers/usb_discovery.h"
#include "keyturn/rig/found_camera.h"

namespace keyturn::app {
namespace {

struct DevicesArgs {
  bool json = false;
  double watch = 0;
};

nlohmann::json toJson(const drivers::UsbCameraInfo& c) {
  char id[16];
  std::snprintf(id, sizeof id, "%04x:%04x", c.vendor_id, c.product_id);
  return {{"model", c.model},   {"bus", c.bus},           {"address", c.address},
          {"port", c.port_path}, {"id", id},               {"serial", c.serial},
          {"node", c.node},     {"accessible", c.accessible}, {"access_error", c.access_error}};
}

void printLine(const drivers::UsbCameraInfo& c, const char* prefix) {
  std::printf("%s%s  bus %03d address %03d (port %s)  %04x:%04x  serial %s  %s\n", prefix, c.model.c_str(), c.bus,
              c.address, c.port_path.empty() ? "?" : c.port_path.c_str(), c.vendor_id, c.product_id,
              c.serial.empty() ? "(unreadable)" : c.serial.c_str(),
              c.accessible ? "accessible" : ("NO ACCESS: " + c.access_error).c_str());
}

nlohmann::json toJson(const drivers::OpenNi2VideoMode& m) {
  return {{"width", m.width}, {"height", m.height}, {"fps", m.fps}, {"format", m.pixel_format}};
}

nlohmann::json toJson(const drivers::OpenNi2DeviceInfo& d) {
  char id[16];
  std::snprintf(id, sizeof id, "%04x:%04x", d.usb_vendor_id, d.usb_product_id);
  nlohmann::json j = {{"uri", d.uri}, {"vendor", d.vendor}, {"name", d.name}, {"id", id}, {"spec", rig::cameraSpecOf(d).toString()}};
  if (!d.error.empty()) {
    j["error"] = d.error;
    return j;
  }
  j["depth_modes"] = nlohmann::json::array();
  for (const auto& m : d.depth_modes) j["depth_modes"].push_back(toJson(m));
  j["depth_mode"] = toJson(d.depth_mode);
  j["hfov_deg"] = d.hfov_deg;
  j["vfov_deg"] = d.vfov_deg;
  j["intrinsics"] = {{"fx", d.intrinsics.fx}, {"fy", d.intrinsics.fy}, {"cx", d.intrinsics.cx}, {"cy", d.intrinsics.cy}};
  j["colour"] = d.has_colour;
  j["ir"] = d.has_ir;
  j["registration"] = d.registration;
  return j;
}

void printOpenNi2(const drivers::OpenNi2DeviceInfo& d) {
  std::printf("%s %s  %04x:%04x  %s\n", d.vendor.c_str(), d.name.c_str(), d.usb_vendor_id, d.usb_product_id,
              rig::cameraSpecOf(d).toString().c_str());
  if (!d.error.empty()) {
    std::printf("  cannot open: %s\n", d.error.c_str());
    return;
  }
  std::printf("  depth %dx%d @ %d fps (%s), field of view %.1f x %.1f deg: fx %.2f fy %.2f cx %.2f cy %.2f\n",
              d.depth_mode.width, d.depth_mode.height, d.depth_mode.fps, d.depth_mode.pixel_format.c_str(), d.hfov_deg,
              d.vfov_deg, d.intrinsics.fx, d.intrinsics.fy, d.intrinsics.cx, d.intrinsics.cy);
  std::string modes;
  for (const auto& m : d.depth_modes)
    modes += (modes.empty() ? "" : ", ") + std::to_string(m.width) + "x" + std::to_string(m.height) + "@" +
             std::to_string(m.fps) + " " + m.pixel_format;
  std::printf("  depth modes: %s\n  colour: %s, IR: %s, depth-to-colour registration: %s\n", modes.c_str(),
              d.has_colour ? "yes" : "no", d.has_ir ? "yes" : "no", d.registration ? "yes" : "no");
}

int runDevices(const DevicesArgs& a) {
  const auto cams = drivers::listSwissRangerCameras();
  // OpenNI2's devices; OpenNI2 failing to start is said, not fatal: the SwissRangers are still listed.
  std::vector<drivers::OpenNi2DeviceInfo> depth_cams;
  std::string openni2_error;
  try {
    depth_cams = drivers::listOpenNi2Devices();
  } catch (const Error& e) {
    openni2_error = e.what();
  }
  bool denied = false;
  for (const auto& c : cams) denied = denied || !c.accessible;
  if (a.json) {
    nlohmann::json j = {{"cameras", nlohmann::json::array()}};
    for (const auto& c : cams) j["cameras"].push_back(toJson(c));
    if (denied) j["udev_rule"] = drivers::swissRangerUdevRule();
    j["hotplug_supported"] = drivers::UsbHotplugWatcher::supported();
    j["openni2"] = nlohmann::json::array();
    for (const auto& d : depth_cams) j["openni2"].push_back(toJson(d));
    if (!openni2_error.empty()) j["openni2_error"] = openni2_error;
    std::cout << j.dump(2) << "\n";
  } else {
    if (cams.empty()) std::printf("No SwissRanger SR3000/SR4000 on USB.\n");
    for (const auto& c : cams) printLine(c, "");
    if (denied) std::printf("\nTo open the camera(s) without root, install this udev rule:\n%s\n",
                            drivers::swissRangerUdevRule().c_str());
    if (!openni2_error.empty()) std::printf("%s\n", openni2_error.c_str());
    else if (depth_cams.empty()) std::printf("No OpenNI2 depth camera.\n");
    for (const auto& d : depth_cams) printOpenNi2(d);
  }
  if (a.watch > 0) {
    if (!drivers::UsbHotplugWatcher::supported()) {
      std::fprintf(stderr, "keyturn devices: this libusb cannot report hot-plug events\n");
      return 1;
    }
    drivers::UsbHotplugWatcher watcher([&](bool arrived, const drivers::UsbCameraInfo& c) {
      if (a.json) std::cout << nlohmann::json{{"event", arrived ? "arrived" : "left"}, {"camera", toJson(c)}}.dump() << "\n";
      else printLine(c, arrived ? "arrived: " : "left:    ");
      std::fflush(stdout);
    });
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(a.watch);
    while (std::chrono::steady_clock::now() < end) watcher.poll(200);
  }
  return 0;
}

}  // namespace

Command addDevicesCommand(CLI::App& app) {
  auto a = std::make_shared<DevicesArgs>();
  auto* cmd = app.add_subcommand("devices", "List SwissRanger cameras on USB (whether they can be opened) and OpenNI2 depth cameras");
  cmd->add_flag("--json", a->json, "One JSON object");
  cmd->add_option("--watch", a->watch, "Then report cameras arriving and leaving for this many seconds");
  return {cmd, [a] { return runDevices(*a); }};
}

}  // namespace keyturn::app
