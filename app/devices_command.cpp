// keyturn devices: SwissRanger cameras on USB, whether this user may open
// them, and the udev rule when not. --watch follows hot-plug events.
#include <csignal>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <thread>

#include "commands.h"
#include "keyturn/drivers/usb_discovery.h"

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

int runDevices(const DevicesArgs& a) {
  const auto cams = drivers::listSwissRangerCameras();
  bool denied = false;
  for (const auto& c : cams) denied = denied || !c.accessible;
  if (a.json) {
    nlohmann::json j = {{"cameras", nlohmann::json::array()}};
    for (const auto& c : cams) j["cameras"].push_back(toJson(c));
    if (denied) j["udev_rule"] = drivers::swissRangerUdevRule();
    j["hotplug_supported"] = drivers::UsbHotplugWatcher::supported();
    std::cout << j.dump(2) << "\n";
  } else {
    if (cams.empty()) std::printf("No SwissRanger SR3000/SR4000 on USB.\n");
    for (const auto& c : cams) printLine(c, "");
    if (denied) std::printf("\nTo open the camera(s) without root, install this udev rule:\n%s\n",
                            drivers::swissRangerUdevRule().c_str());
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
  auto* cmd = app.add_subcommand("devices", "List SwissRanger cameras on USB and whether they can be opened");
  cmd->add_flag("--json", a->json, "One JSON object");
  cmd->add_option("--watch", a->watch, "Then report cameras arriving and leaving for this many seconds");
  return {cmd, [a] { return runDevices(*a); }};
}

}  // namespace keyturn::app
