#include "keyturn/drivers/sr4000_camera.h"

#include <arpa/inet.h>

#include <chrono>
#include <cmath>
#include <thread>

#include "keyturn/core/error.h"
#include "keyturn/drivers/retry.h"

namespace keyturn::drivers {

Sr4000Connection Sr4000Connection::parse(const std::string& text) {
  Sr4000Connection c;
  if (text == "usb") return c;
  if (text.rfind("usb:", 0) == 0) {
    const std::string s = text.substr(4);
    char* end = nullptr;
    const unsigned long v = std::strtoul(s.c_str(), &end, 0);
    if (s.empty() || *end != '\0' || v > 0xFFFFFFFFul)
      throw Error("camera '" + text + "': expected usb:SERIAL with a number");
    c.serial = static_cast<unsigned>(v);
    return c;
  }
  if (text.rfind("eth:", 0) == 0) {
    c.kind = Kind::Ethernet;
    c.address = text.substr(4);
    in_addr addr{};
    if (::inet_pton(AF_INET, c.address.c_str(), &addr) != 1)
      throw Error("camera '" + text + "': expected eth:IPv4-ADDRESS");
    return c;
  }
  throw Error("camera '" + text + "': expected usb, usb:SERIAL or eth:IP");
}

std::string Sr4000Connection::describe() const {
  if (kind == Kind::Ethernet) return "SR4000 at " + address;
  if (kind == Kind::Simulator) return simulator_config.empty() ? "simulated SR4000" : "simulated SR4000 (" + simulator_config + ")";
  return serial ? "SR4000 USB serial " + std::to_string(serial) : "first SR4000 on USB";
}

Sr4000Camera::Sr4000Camera(std::shared_ptr<MesaSrLibrary> lib, Sr4000Connection connection,
                           Sr4000Options options)
    : lib_(std::move(lib)), connection_(std::move(connection)), options_(std::move(options)) {
  open();
  configure(wanted_);
}

Sr4000Camera::~Sr4000Camera() { close(); }

std::string Sr4000Camera::name() const {
  return options_.name.empty() ? connection_.describe() : options_.name;
}

void Sr4000Camera::fail(const std::string& what) const {
  throw Error(name() + " (" + lib_->path + "): " + what);
}

void Sr4000Camera::open() {
  SRCAM cam = nullptr;
  int n = 0;
  if (connection_.kind == Sr4000Connection::Kind::Simulator) {
    if (!lib_->KTSIM_OpenWithConfig) fail("not libmesasr-sim: it has no KTSIM_OpenWithConfig to take the simulator's configuration");
    n = lib_->KTSIM_OpenWithConfig(&cam, connection_.simulator_config.c_str());
  } else if (connection_.kind == Sr4000Connection::Kind::Ethernet) {
    n = lib_->SR_OpenETH(&cam, connection_.address.c_str());
  } else {
    n = lib_->SR_OpenUSB(&cam, connection_.serial);
  }
  if (n <= 0 || !cam) fail("could not open the camera (open returned " + std::to_string(n) + ")");
  cam_ = cam;
  char buf[256] = {0};
  if (lib_->SR_GetDeviceString) lib_->SR_GetDeviceString(cam_, buf, sizeof buf);
  device_ = buf;
  serial_ = lib_->SR_ReadSerial ? lib_->SR_ReadSerial(cam_) : 0;
}

void Sr4000Camera::close() {
  if (cam_) lib_->SR_Close(cam_);
  cam_ = nullptr;
  images_ = nullptr;
  image_count_ = 0;
}

// SR_SetMode reallocates the image buffers, so the list is fetched again after it.
void Sr4000Camera::refreshImageList() {
  images_ = nullptr;
  image_count_ = lib_->SR_GetImageList(cam_, &images_);
  if (image_count_ < 2 || !images_) fail("image list unavailable (" + std::to_string(image_count_) + " images)");
}

void Sr4000Camera::configure(const TofSettings& s) {
  wanted_ = s;
  if (lib_->SR_SetMode(cam_, static_cast<int>(s.acquire_mode)) < 0) fail("SR_SetMode refused");
  refreshImageList();
  if (lib_->SR_SetIntegrationTime && lib_->SR_SetIntegrationTime(cam_, s.integration_time) < 0)
    fail("SR_SetIntegrationTime refused " + std::to_string(s.integration_time));
  if (lib_->SR_SetAutoExposure) {
    const auto& a = s.auto_exposure;
    // A minimum integration time of 0xFF switches auto-exposure off.
    const int rc = a.enabled ? lib_->SR_SetAutoExposure(cam_, a.min_int_time, a.max_int_time,
                                                        a.percent_over_pos, a.desired_pos)
                             : lib_->SR_SetAutoExposure(cam_, 0xFF, 0, 0, 0);
    if (rc < 0) fail("SR_SetAutoExposure refused");
  }
  if (lib_->SR_SetModulationFrequency &&
      lib_->SR_SetModulationFrequency(cam_, static_cast<ModulationFrq>(s.modulation_frequency)) < 0)
    fail("SR_SetModulationFrequency refused " + std::to_string(modulationMHz(s.modulation_frequency)) + " MHz");
  if (lib_->SR_SetAmplitudeThreshold && lib_->SR_SetAmplitudeThreshold(cam_, s.amplitude_threshold) < 0)
    fail("SR_SetAmplitudeThreshold refused");
  if (lib_->SR_SetDistanceOffset && lib_->SR_SetDistanceOffset(cam_, s.distance_offset) < 0)
    fail("SR_SetDistanceOffset refused");
  if (lib_->SR_SetTimeout) lib_->SR_SetTimeout(cam_, s.timeout_ms);
}

TofSettings Sr4000Camera::settings() const {
  TofSettings s = wanted_;  // auto-exposure and timeout cannot be read back
  if (lib_->SR_GetMode) s.acquire_mode = static_cast<std::uint32_t>(lib_->SR_GetMode(cam_));
  if (lib_->SR_GetIntegrationTime) s.integration_time = lib_->SR_GetIntegrationTime(cam_);
  if (lib_->SR_GetModulationFrequency) s.modulation_frequency = lib_->SR_GetModulationFrequency(cam_);
  if (lib_->SR_GetAmplitudeThreshold) s.amplitude_threshold = lib_->SR_GetAmplitudeThreshold(cam_);
  if (lib_->SR_GetDistanceOffset) s.distance_offset = lib_->SR_GetDistanceOffset(cam_);
  return s;
}

std::uint8_t Sr4000Camera::firmwareVersion() const {
  return lib_->SR_GetReg ? lib_->SR_GetReg(cam_, SR4000_REG_FIRMWARE) : 0;
}

TofFrame Sr4000Camera::acquireOnce() {
  const unsigned rows = lib_->SR_GetRows(cam_), cols = lib_->SR_GetCols(cam_);
  const std::size_t n = static_cast<std::size_t>(rows) * cols;
  const int bytes = lib_->SR_Acquire(cam_);
  if (bytes < 0) throw Error("SR_Acquire failed (" + std::to_string(bytes) + ")");
  // Distance and amplitude, 16 bit each; the confidence map is not counted.
  if (static_cast<std::size_t>(bytes) != 2 * n * sizeof(std::uint16_t))
    throw Error("corrupt frame: " + std::to_string(bytes) + " bytes transferred, expected " +
                std::to_string(2 * n * sizeof(std::uint16_t)));

  TofFrame f;
  f.width = cols;
  f.height = rows;
  f.timestamp = std::chrono::system_clock::now();
  f.device = device_;
  f.serial = serial_;
  f.sequence = ++sequence_;
  refreshImageList();
  for (int i = 0; i < image_count_; ++i) {
    const ImgEntry& e = images_[i];
    if (e.dataType != DT_USHORT || static_cast<std::size_t>(e.width) * e.height != n || !e.data) continue;
    const auto* d = static_cast<const std::uint16_t*>(e.data);
    if (e.imgType == IT_DISTANCE) f.distance.assign(d, d + n);
    else if (e.imgType == IT_AMPLITUDE) f.amplitude.assign(d, d + n);
    else if (e.imgType == IT_CONF_MAP) f.confidence.assign(d, d + n);
  }
  if (f.distance.empty() || f.amplitude.empty()) throw Error("frame lacks a distance or amplitude image");

  std::vector<float> x(n), y(n), z(n);
  if (lib_->SR_CoordTrfFlt(cam_, x.data(), y.data(), z.data(), sizeof(float), sizeof(float), sizeof(float)) < 0)
    throw Error("SR_CoordTrfFlt failed");
  Cloud& c = f.cloud;
  c.width = cols;
  c.height = rows;
  c.points.resize(n);
  c.amplitude.resize(n);
  if (!f.confidence.empty()) c.confidence.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    // libMesaSR's x and y point left and up; negate them for the right-handed
    // optical frame (x right, y down, z forward), as the ROS driver does.
    c.points[i] = f.distance[i] == 0 ? Eigen::Vector3f::Constant(std::nanf(""))
                                     : Eigen::Vector3f(-x[i], -y[i], z[i]);
    c.amplitude[i] = f.amplitude[i];
    if (!f.confidence.empty()) c.confidence[i] = f.confidence[i] / 65535.0f;
  }
  f.settings = wanted_;
  return f;
}

TofFrame Sr4000Camera::acquire() {
  return withReopening(
      name() + " (" + lib_->path + ")", RetryPolicy{options_.reconnect_attempts, options_.backoff_initial_ms},
      options_.log,
      [&] {
        if (!cam_) throw Error("not open");  // the last reopen failed
        return acquireOnce();
      },
      [&] {
        close();
        open();
        configure(wanted_);
        ++reconnects_;
      });
}

}  // namespace keyturn::drivers
