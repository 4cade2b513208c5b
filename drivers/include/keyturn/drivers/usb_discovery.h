#pragma once
// Finding SwissRanger cameras on USB with libusb-1.0, and whether this user may
// open them.
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace keyturn::drivers {

struct UsbCameraInfo {
  std::string model;        // "SR4000" or "SR3000"
  int bus = 0;
  int address = 0;
  std::string port_path;    // sysfs name, e.g. "1-2.4"
  unsigned vendor_id = 0, product_id = 0;
  std::string serial;       // from sysfs; empty when not readable
  std::string node;         // /dev/bus/usb/BBB/DDD
  bool accessible = false;  // this process may open it read/write
  std::string access_error; // why not
};

// Known ids: SR4000 1ad2:0075; SR3000 1ad2:0074 and (older) 0852:0074.
const char* swissRangerModel(unsigned vendor_id, unsigned product_id);  // nullptr if not one

// Every attached SR3000/SR4000; other USB devices are ignored. Throws
// keyturn::Error when libusb cannot be initialised.
std::vector<UsbCameraInfo> listSwissRangerCameras();

// The udev rule that grants access (MESA shipped one like it).
std::string swissRangerUdevRule();

// Hot-plug notifications where libusb supports them. The callback runs on the
// thread that calls poll().
class UsbHotplugWatcher {
 public:
  using Callback = std::function<void(bool arrived, const UsbCameraInfo& camera)>;
  explicit UsbHotplugWatcher(Callback cb);
  ~UsbHotplugWatcher();
  static bool supported();
  void poll(int timeout_ms);  // handles pending events

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace keyturn::drivers
