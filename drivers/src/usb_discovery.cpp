#include "keyturn/drivers/usb_discovery.h"

#include <libusb-1.0/libusb.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "keyturn/core/error.h"

namespace keyturn::drivers {

const char* swissRangerModel(unsigned vid, unsigned pid) {
  if (vid == 0x1ad2 && pid == 0x0075) return "SR4000";
  if ((vid == 0x1ad2 || vid == 0x0852) && pid == 0x0074) return "SR3000";
  return nullptr;
}

std::string swissRangerUdevRule() {
  return "# /etc/udev/rules.d/60-swissranger.rules: let users of group plugdev open MESA SwissRanger cameras\n"
         "SUBSYSTEM==\"usb\", ATTRS{idVendor}==\"1ad2\", MODE=\"0660\", GROUP=\"plugdev\"\n"
         "SUBSYSTEM==\"usb\", ATTRS{idVendor}==\"0852\", ATTRS{idProduct}==\"0074\", MODE=\"0660\", GROUP=\"plugdev\"\n"
         "# then: sudo udevadm control --reload-rules && sudo udevadm trigger, and re-plug the camera";
}

namespace {

std::string readSysfs(const std::string& port_path, const char* attr) {
  std::ifstream in("/sys/bus/usb/devices/" + port_path + "/" + attr);
  std::string s;
  std::getline(in, s);
  return s;
}

// The sysfs name ("1-3.1") of the device at bus/address, found by its busnum
// and devnum attributes; empty if sysfs does not list it.
std::string sysfsName(int bus, int address) {
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator("/sys/bus/usb/devices", ec)) {
    const std::string name = e.path().filename().string();
    if (name.find(':') != std::string::npos) continue;  // interfaces, not devices
    if (readSysfs(name, "busnum") == std::to_string(bus) && readSysfs(name, "devnum") == std::to_string(address))
      return name;
  }
  return "";
}

bool describe(libusb_device* dev, UsbCameraInfo& out) {
  libusb_device_descriptor d{};
  if (libusb_get_device_descriptor(dev, &d) != 0) return false;
  const char* model = swissRangerModel(d.idVendor, d.idProduct);
  if (!model) return false;
  out.model = model;
  out.vendor_id = d.idVendor;
  out.product_id = d.idProduct;
  out.bus = libusb_get_bus_number(dev);
  out.address = libusb_get_device_address(dev);
  out.port_path = sysfsName(out.bus, out.address);
  // The serial string descriptor needs a control transfer (and access);
  // sysfs has it for everyone.
  out.serial = out.port_path.empty() ? "" : readSysfs(out.port_path, "serial");
  char node[32];
  std::snprintf(node, sizeof node, "/dev/bus/usb/%03d/%03d", out.bus, out.address);
  out.node = node;
  return true;
}

void checkAccess(libusb_device* dev, UsbCameraInfo& out) {
  libusb_device_handle* h = nullptr;
  const int rc = libusb_open(dev, &h);
  out.accessible = rc == 0;
  if (h) libusb_close(h);
  if (rc == LIBUSB_ERROR_ACCESS) out.access_error = "permission denied on " + out.node;
  else if (rc != 0) out.access_error = std::string(libusb_error_name(rc)) + " opening " + out.node;
}

}  // namespace

std::vector<UsbCameraInfo> listSwissRangerCameras() {
  libusb_context* ctx = nullptr;
  if (const int rc = libusb_init(&ctx); rc != 0)
    throw Error(std::string("USB: libusb could not start: ") + libusb_error_name(rc));
  libusb_device** list = nullptr;
  const ssize_t n = libusb_get_device_list(ctx, &list);
  std::vector<UsbCameraInfo> out;
  for (ssize_t i = 0; i < n; ++i) {
    UsbCameraInfo info;
    if (!describe(list[i], info)) continue;
    checkAccess(list[i], info);
    out.push_back(info);
  }
  if (list) libusb_free_device_list(list, 1);
  libusb_exit(ctx);
  return out;
}

struct UsbHotplugWatcher::Impl {
  libusb_context* ctx = nullptr;
  libusb_hotplug_callback_handle handle = 0;
  Callback cb;
};

namespace {
int LIBUSB_CALL onHotplug(libusb_context*, libusb_device* dev, libusb_hotplug_event event, void* user) {
  auto* impl = static_cast<UsbHotplugWatcher::Impl*>(user);
  UsbCameraInfo info;
  if (!describe(dev, info)) return 0;
  const bool arrived = event == LIBUSB_HOTPLUG_EVENT_DEVICE_ARRIVED;
  if (arrived) checkAccess(dev, info);
  impl->cb(arrived, info);
  return 0;  // stay registered
}
}  // namespace

bool UsbHotplugWatcher::supported() { return libusb_has_capability(LIBUSB_CAP_HAS_HOTPLUG) != 0; }

UsbHotplugWatcher::UsbHotplugWatcher(Callback cb) : impl_(std::make_unique<Impl>()) {
  impl_->cb = std::move(cb);
  if (!supported()) throw Error("USB: this libusb has no hot-plug support");
  if (const int rc = libusb_init(&impl_->ctx); rc != 0)
    throw Error(std::string("USB: libusb could not start: ") + libusb_error_name(rc));
  const int rc = libusb_hotplug_register_callback(
      impl_->ctx,
      static_cast<libusb_hotplug_event>(LIBUSB_HOTPLUG_EVENT_DEVICE_ARRIVED | LIBUSB_HOTPLUG_EVENT_DEVICE_LEFT),
      LIBUSB_HOTPLUG_NO_FLAGS, LIBUSB_HOTPLUG_MATCH_ANY, LIBUSB_HOTPLUG_MATCH_ANY,
      LIBUSB_HOTPLUG_MATCH_ANY, onHotplug, impl_.get(), &impl_->handle);
  if (rc != LIBUSB_SUCCESS) {
    libusb_exit(impl_->ctx);
    throw Error(std::string("USB: hot-plug registration failed: ") + libusb_error_name(rc));
  }
}

UsbHotplugWatcher::~UsbHotplugWatcher() {
  libusb_hotplug_deregister_callback(impl_->ctx, impl_->handle);
  libusb_exit(impl_->ctx);
}

void UsbHotplugWatcher::poll(int timeout_ms) {
  timeval tv{timeout_ms / 1000, (timeout_ms % 1000) * 1000};
  libusb_handle_events_timeout_completed(impl_->ctx, &tv, nullptr);
}

}  // namespace keyturn::drivers
