// A found camera opens as the spec rig makes of it (found_camera.h): the one way from a discovered
// device to a CameraSpec, for `keyturn devices` and the studio's lists.
#include <gtest/gtest.h>

#include "keyturn/rig/found_camera.h"

namespace keyturn {
namespace {

drivers::UsbCameraInfo sr4000(const std::string& serial, bool accessible) {
  drivers::UsbCameraInfo c;
  c.model = "SR4000";
  c.serial = serial;
  c.port_path = "1-2.4";
  c.accessible = accessible;
  c.access_error = accessible ? "" : "permission denied";
  return c;
}

TEST(FoundCamera, ASwissRangerOpensByItsSerialAndReadsAsOneLine) {
  const rig::FoundCamera f = rig::foundCamera(sr4000("4000123", true));
  EXPECT_EQ(f.spec.kind, rig::CameraSpec::Kind::Usb);
  EXPECT_EQ(f.spec.usb_serial, 4000123u);
  EXPECT_EQ(f.spec.toString(), "usb:4000123");
  EXPECT_EQ(rig::CameraSpec::parse(f.spec.toString()), f.spec);
  EXPECT_EQ(f.label, "SR4000 4000123 on USB 1-2.4");
  EXPECT_EQ(rig::foundCamera(sr4000("4000123", false)).label, "SR4000 4000123 on USB 1-2.4 (no access: permission denied)");
  // A serial sysfs did not show, or not a number: the first SwissRanger found.
  EXPECT_EQ(rig::foundCamera(sr4000("", true)).spec.toString(), "usb");
  EXPECT_EQ(rig::foundCamera(sr4000("", true)).label, "SR4000 on USB 1-2.4");
  EXPECT_EQ(rig::cameraSpecOf(sr4000("n/a", true)).usb_serial, 0u);
}

TEST(FoundCamera, AnOpenNi2DeviceOpensByItsUriVerbatim) {
  drivers::OpenNi2DeviceInfo d;
  d.uri = "1d27/0601@2/5";
  d.vendor = "PrimeSense";
  d.name = "PS1080";
  const rig::FoundCamera f = rig::foundCamera(d);
  EXPECT_EQ(f.spec.kind, rig::CameraSpec::Kind::OpenNi2);
  EXPECT_EQ(f.spec.openni2_uri, "1d27/0601@2/5");
  EXPECT_EQ(f.spec.toString(), "openni2:1d27/0601@2/5");
  EXPECT_EQ(rig::CameraSpec::parse(f.spec.toString()), f.spec);
  EXPECT_EQ(f.label, "PrimeSense PS1080 (1d27/0601@2/5)");
  d.error = "cannot open: busy";
  EXPECT_EQ(rig::foundCamera(d).label, "PrimeSense PS1080 (1d27/0601@2/5): cannot open: busy");
  EXPECT_EQ(rig::openNi2CameraSpec("").toString(), "openni2");  // the first device found
}

}  // namespace
}  // namespace keyturn
