// Hot-plug through libusb on a umockdev testbed made in-process: a camera
// plugged in and pulled out again. Runs under umockdev-wrapper.
#include <gtest/gtest.h>
#include <umockdev.h>

#include <cstdlib>
#include <cstring>
#include <vector>

#include "keyturn/drivers/usb_discovery.h"
#include "support/ci_skip.h"

using namespace keyturn::drivers;

namespace {
gchar* addUsbDevice(UMockdevTestbed* tb, const char* name, const char* devnum, const char* vid, const char* pid,
                    const char* serial) {
  const std::string node = std::string("/dev/bus/usb/001/") + devnum;
  const std::string devnum_attr = std::to_string(std::atoi(devnum));  // sysfs writes "5", udev "005"
  gchar* sys = umockdev_testbed_add_device(tb, "usb", name, nullptr, "busnum", "1", "devnum", devnum_attr.c_str(), "idVendor",
                                           vid, "idProduct", pid, "serial", serial, nullptr, "BUSNUM", "001",
                                           "DEVNUM", devnum, "DEVTYPE", "usb_device", "DEVNAME", node.c_str(),
                                           nullptr);
  const unsigned v = std::strtoul(vid, nullptr, 16), p = std::strtoul(pid, nullptr, 16);
  guint8 desc[] = {0x12, 0x01, 0x00, 0x02, 0xff, 0, 0, 0x40, static_cast<guint8>(v & 0xff), static_cast<guint8>(v >> 8),
                   static_cast<guint8>(p & 0xff), static_cast<guint8>(p >> 8), 0, 1, 1, 2, 3, 1,
                   9, 2, 0x12, 0, 1, 1, 0, 0x80, 0x32, 9, 4, 0, 0, 0, 0, 0, 0, 0};
  umockdev_testbed_set_attribute_binary(tb, sys, "descriptors", desc, sizeof desc);
  return sys;
}
}  // namespace

TEST(UsbHotplug, ReportsACameraArrivingAndLeavingButNotOtherDevices) {
  const char* preload = std::getenv("LD_PRELOAD");
  // ctest runs it under umockdev-wrapper, and Debian's libusb has hot-plug on Linux (both in
  // scripts/install-deps.sh): on CI neither is a skip.
  if (!preload || !std::strstr(preload, "umockdev")) KEYTURN_SKIP_UNLESS_CI("needs umockdev-wrapper");
  if (!UsbHotplugWatcher::supported()) KEYTURN_SKIP_UNLESS_CI("libusb without hot-plug support");
  UMockdevTestbed* tb = umockdev_testbed_new();
  std::vector<std::pair<bool, UsbCameraInfo>> events;
  UsbHotplugWatcher watcher([&](bool arrived, const UsbCameraInfo& c) { events.emplace_back(arrived, c); });

  gchar* mouse = addUsbDevice(tb, "1-4", "007", "046d", "c52b", "NOTACAMERA");
  umockdev_testbed_uevent(tb, mouse, "add");
  gchar* cam = addUsbDevice(tb, "1-2", "005", "1ad2", "0075", "4000123");
  umockdev_testbed_uevent(tb, cam, "add");
  for (int i = 0; i < 30 && events.empty(); ++i) watcher.poll(100);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_TRUE(events[0].first);
  EXPECT_EQ(events[0].second.model, "SR4000");
  EXPECT_EQ(events[0].second.serial, "4000123");
  EXPECT_EQ(events[0].second.address, 5);

  umockdev_testbed_uevent(tb, cam, "remove");
  umockdev_testbed_remove_device(tb, cam);
  for (int i = 0; i < 30 && events.size() < 2; ++i) watcher.poll(100);
  ASSERT_EQ(events.size(), 2u);
  EXPECT_FALSE(events[1].first);
  EXPECT_EQ(events[1].second.model, "SR4000");
  g_free(cam);
  g_free(mouse);
  g_object_unref(tb);
}
