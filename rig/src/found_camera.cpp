#include "keyturn/rig/found_camera.h"

#include <exception>

namespace keyturn::rig {

CameraSpec cameraSpecOf(const drivers::UsbCameraInfo& camera) {
  CameraSpec spec;
  spec.kind = CameraSpec::Kind::Usb;
  try {
    spec.usb_serial = static_cast<unsigned>(std::stoul(camera.serial));
  } catch (const std::exception&) {
    spec.usb_serial = 0;  // unreadable: the first camera found
  }
  return spec;
}

CameraSpec openNi2CameraSpec(const std::string& uri) {
  CameraSpec spec;
  spec.kind = CameraSpec::Kind::OpenNi2;
  spec.openni2_uri = uri;
  return spec;
}

CameraSpec cameraSpecOf(const drivers::OpenNi2DeviceInfo& device) { return openNi2CameraSpec(device.uri); }

FoundCamera foundCamera(const drivers::UsbCameraInfo& c) {
  std::string label = c.model + (c.serial.empty() ? "" : " " + c.serial) + " on USB " + c.port_path;
  if (!c.accessible) label += " (no access: " + c.access_error + ")";
  return {cameraSpecOf(c), label};
}

FoundCamera foundCamera(const drivers::OpenNi2DeviceInfo& d) {
  return {cameraSpecOf(d), d.vendor + " " + d.name + " (" + d.uri + ")" + (d.error.empty() ? "" : ": " + d.error)};
}

std::vector<FoundCamera> findUsbCameras() {
  std::vector<FoundCamera> out;
  for (const auto& c : drivers::listSwissRangerCameras()) out.push_back(foundCamera(c));
  return out;
}

std::vector<FoundCamera> findOpenNi2Cameras() {
  std::vector<FoundCamera> out;
  for (const auto& d : drivers::listOpenNi2Devices()) out.push_back(foundCamera(d));
  return out;
}

}  // namespace keyturn::rig
