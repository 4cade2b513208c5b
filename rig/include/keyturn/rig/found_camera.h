#pragma once
// A camera found on this machine, as the spec that opens it: the one way from a discovered device
// (a SwissRanger on USB, an OpenNI2 device) to a CameraSpec, as librealsense's device_info is the
// one way from a found device to an opened one. `keyturn devices` and the studio's device lists
// name a found camera only through these, never by spec text they assemble themselves.
#include <string>
#include <vector>

#include "keyturn/drivers/openni2_camera.h"
#include "keyturn/drivers/usb_discovery.h"
#include "keyturn/rig/device_spec.h"

namespace keyturn::rig {

struct FoundCamera {
  CameraSpec spec;    // opens this device
  std::string label;  // one line for a list: "SR4000 4000123 on USB 1-2", "PrimeSense PS1080 (URI)",
                      // with why it cannot be opened when it cannot ("… (no access: …)", "…: ERROR")
};

// usb:SERIAL; a serial sysfs does not show (or not a number) is 0, the first SwissRanger found.
CameraSpec cameraSpecOf(const drivers::UsbCameraInfo& camera);
// openni2:URI, OpenNI2's URI verbatim.
CameraSpec cameraSpecOf(const drivers::OpenNi2DeviceInfo& device);
// The OpenNI2 camera with this URI ("": the first device found), e.g. a URI typed by hand.
CameraSpec openNi2CameraSpec(const std::string& uri);

FoundCamera foundCamera(const drivers::UsbCameraInfo& camera);
FoundCamera foundCamera(const drivers::OpenNi2DeviceInfo& device);

// The SwissRangers on USB; throws keyturn::Error when libusb cannot be initialised.
std::vector<FoundCamera> findUsbCameras();
// The OpenNI2 depth cameras; throws keyturn::Error when OpenNI2 cannot start.
std::vector<FoundCamera> findOpenNi2Cameras();

}  // namespace keyturn::rig
