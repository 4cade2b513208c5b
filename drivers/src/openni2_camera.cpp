#include "keyturn/drivers/openni2_camera.h"

#include <OpenNI.h>
#include <dlfcn.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <set>

#include "keyturn/core/error.h"
#include "keyturn/drivers/retry.h"
#include "keyturn/drivers/oni_recording_check.h"

namespace keyturn::drivers {
namespace {

constexpr double kPi = 3.14159265358979323846;

// OpenNI2's last error as part of one line: its tabs and line breaks folded into single spaces.
std::string openNiError() {
  std::string out;
  for (const char* c = openni::OpenNI::getExtendedError(); c && *c; ++c) {
    const bool space = *c == '\n' || *c == '\t' || *c == '\r' || *c == ' ';
    if (space) {
      if (!out.empty() && out.back() != ' ') out += ' ';
    } else {
      out += *c;
    }
  }
  while (!out.empty() && out.back() == ' ') out.pop_back();
  return out.empty() ? "no detail" : out;
}

// OpenNI2 keeps one context per process; it is started on first use and left running (its
// shutdown unloads the drivers, which other threads' devices may still use).
void startOpenNi2() {
  static std::mutex mutex;
  static bool started = false;
  std::lock_guard<std::mutex> l(mutex);
  if (started) return;
  if (openni::OpenNI::initialize() != openni::STATUS_OK)
    throw Error(std::string("OpenNI2 could not start: ") + openNiError());
  started = true;
}

// Where libOpenNI2 looks for its drivers: OpenNI2/Drivers beside the library it was loaded from,
// and the folders its links there lead to (keyturn's folder links the system's drivers).
std::string driverFolders() {
  namespace fs = std::filesystem;
  Dl_info info{};
  if (::dladdr(reinterpret_cast<void*>(&oniInitialize), &info) == 0 || !info.dli_fname) return "OpenNI2/Drivers";
  const fs::path folder = fs::path(info.dli_fname).parent_path() / "OpenNI2" / "Drivers";
  std::set<std::string> linked;
  std::error_code ec;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    std::error_code link_ec;
    if (!it->is_symlink(link_ec)) continue;
    const fs::path target = fs::read_symlink(it->path(), link_ec);
    if (!link_ec) linked.insert((folder / target).parent_path().lexically_normal().string());
  }
  linked.erase(folder.lexically_normal().string());
  std::string out = folder.string();
  for (const auto& f : linked) out += (f == *linked.begin() ? " (links into " : ", ") + f;
  return linked.empty() ? out : out + ")";
}

std::string pixelFormatName(openni::PixelFormat f) {
  switch (f) {
    case openni::PIXEL_FORMAT_DEPTH_1_MM: return "depth 1 mm";
    case openni::PIXEL_FORMAT_DEPTH_100_UM: return "depth 100 um";
    case openni::PIXEL_FORMAT_SHIFT_9_2: return "shift 9.2";
    case openni::PIXEL_FORMAT_SHIFT_9_3: return "shift 9.3";
    case openni::PIXEL_FORMAT_RGB888: return "rgb888";
    case openni::PIXEL_FORMAT_YUV422: return "yuv422";
    case openni::PIXEL_FORMAT_GRAY8: return "gray8";
    case openni::PIXEL_FORMAT_GRAY16: return "gray16";
    case openni::PIXEL_FORMAT_JPEG: return "jpeg";
    case openni::PIXEL_FORMAT_YUYV: return "yuyv";
  }
  return "format " + std::to_string(static_cast<int>(f));
}

double depthUnitMetres(openni::PixelFormat f) {
  if (f == openni::PIXEL_FORMAT_DEPTH_1_MM) return 0.001;
  if (f == openni::PIXEL_FORMAT_DEPTH_100_UM) return 0.0001;
  return 0;  // the PS1080's raw shift formats are not depth
}

OpenNi2VideoMode modeOf(const openni::VideoMode& m) {
  return {m.getResolutionX(), m.getResolutionY(), m.getFps(), pixelFormatName(m.getPixelFormat())};
}

// The stream's mode when it already gives depth in millimetres or 100 µm, else the device's
// millimetre mode at the same resolution (nearest frame rate).
void chooseDepthMode(openni::VideoStream& depth) {
  const openni::VideoMode current = depth.getVideoMode();
  if (depthUnitMetres(current.getPixelFormat()) > 0) return;
  const auto& modes = depth.getSensorInfo().getSupportedVideoModes();
  for (int i = 0; i < modes.getSize(); ++i)
    if (modes[i].getPixelFormat() == openni::PIXEL_FORMAT_DEPTH_1_MM &&
        modes[i].getResolutionX() == current.getResolutionX() &&
        modes[i].getResolutionY() == current.getResolutionY() && depth.setVideoMode(modes[i]) == openni::STATUS_OK)
      return;
  for (int i = 0; i < modes.getSize(); ++i)
    if (depthUnitMetres(modes[i].getPixelFormat()) > 0 && depth.setVideoMode(modes[i]) == openni::STATUS_OK) return;
}

// The colour stream in RGB888 at the depth image's size when the device offers it (registration
// maps depth onto the colour image pixel for pixel only when both have one size).
bool chooseColourMode(openni::VideoStream& colour, int width, int height) {
  const auto& modes = colour.getSensorInfo().getSupportedVideoModes();
  for (int i = 0; i < modes.getSize(); ++i)
    if (modes[i].getPixelFormat() == openni::PIXEL_FORMAT_RGB888 && modes[i].getResolutionX() == width &&
        modes[i].getResolutionY() == height)
      return colour.setVideoMode(modes[i]) == openni::STATUS_OK;
  return false;
}

// keyturn's simulated camera (simulators/openni2_sim/), listed after the real devices.
bool isSimulatedUri(const std::string& uri) { return uri.rfind("keyturn-sim://", 0) == 0; }

std::vector<std::string> presentUris() {
  openni::Array<openni::DeviceInfo> list;
  openni::OpenNI::enumerateDevices(&list);
  std::vector<std::string> out;
  for (int i = 0; i < list.getSize(); ++i) out.emplace_back(list[i].getUri());
  return out;
}

}  // namespace

DepthIntrinsics intrinsicsFromFieldOfView(double hfov, double vfov, std::uint32_t width, std::uint32_t height) {
  if (!(hfov > 0 && hfov < kPi) || !(vfov > 0 && vfov < kPi))
    throw Error("field of view " + std::to_string(hfov * 180 / kPi) + "° × " + std::to_string(vfov * 180 / kPi) +
                "°: each must lie between 0° and 180°");
  if (width == 0 || height == 0) throw Error("an image of " + std::to_string(width) + " × " + std::to_string(height) + " pixels has no pinhole");
  DepthIntrinsics k;
  k.fx = width / (2.0 * std::tan(hfov / 2));
  k.fy = height / (2.0 * std::tan(vfov / 2));
  k.cx = (width - 1) / 2.0;
  k.cy = (height - 1) / 2.0;
  return k;
}

TofFrame depthCameraFrame(const std::uint16_t* depth, std::uint32_t width, std::uint32_t height,
                          std::size_t stride_bytes, const DepthIntrinsics& intrinsics, double depth_unit_m) {
  if (stride_bytes < width * sizeof(std::uint16_t))
    throw Error("depth image: row stride " + std::to_string(stride_bytes) + " bytes is shorter than " +
                std::to_string(width) + " pixels");
  TofFrame f;
  f.width = width;
  f.height = height;
  f.distance.resize(static_cast<std::size_t>(width) * height);
  const auto* bytes = reinterpret_cast<const std::uint8_t*>(depth);
  for (std::uint32_t v = 0; v < height; ++v)
    std::memcpy(&f.distance[static_cast<std::size_t>(v) * width], bytes + v * stride_bytes, width * sizeof(std::uint16_t));
  f.cloud = depthImageToCloud(f.distance, width, height, intrinsics, depth_unit_m);
  DepthCameraFrame d;
  d.depth_unit_m = depth_unit_m;
  d.intrinsics = intrinsics;
  f.depth_camera = d;
  return f;
}

std::string firstOpenNi2Device(const std::vector<std::string>& uris) {
  for (const auto& uri : uris)
    if (!isSimulatedUri(uri)) return uri;
  return uris.empty() ? "" : uris.front();
}

std::vector<OpenNi2DeviceInfo> listOpenNi2Devices() {
  startOpenNi2();
  openni::Array<openni::DeviceInfo> list;
  openni::OpenNI::enumerateDevices(&list);
  std::vector<OpenNi2DeviceInfo> out;
  for (int i = 0; i < list.getSize(); ++i) {
    OpenNi2DeviceInfo info;
    info.uri = list[i].getUri();
    info.vendor = list[i].getVendor();
    info.name = list[i].getName();
    info.usb_vendor_id = list[i].getUsbVendorId();
    info.usb_product_id = list[i].getUsbProductId();
    try {
      OpenNi2Options o;
      o.uri = info.uri;
      o.reconnect_attempts = 0;
      OpenNi2Camera camera(o);  // opened as grab would open it: the same mode and intrinsics
      OpenNi2DeviceInfo opened = camera.info();
      opened.vendor = info.vendor;
      opened.name = info.name;
      opened.usb_vendor_id = info.usb_vendor_id;
      opened.usb_product_id = info.usb_product_id;
      info = opened;
    } catch (const Error& e) {
      info.error = e.what();
    }
    out.push_back(info);
  }
  std::stable_partition(out.begin(), out.end(), [](const OpenNi2DeviceInfo& d) { return !isSimulatedUri(d.uri); });
  return out;
}

// The device and its streams; none of OpenNI2's types leave this file.
struct OpenNi2Camera::Streams {
  openni::Device device;
  openni::VideoStream depth, colour, ir;
  bool has_colour = false, has_ir = false, registered = false;
  double depth_unit_m = 0.001;
  int frames_in_file = 0, frames_read = 0;
  OpenNi2DeviceInfo info;

  ~Streams() {
    if (has_colour) colour.stop(), colour.destroy();
    if (has_ir) ir.stop(), ir.destroy();
    depth.stop();
    depth.destroy();
    device.close();
  }
};

OpenNi2Camera::OpenNi2Camera(OpenNi2Options options) : options_(std::move(options)) { open(); }

OpenNi2Camera::~OpenNi2Camera() { close(); }

std::string OpenNi2Camera::name() const {
  if (!options_.oni_file.empty()) return "recording " + options_.oni_file;
  if (!options_.uri.empty()) return "OpenNI2 device " + options_.uri;
  return "OpenNI2 camera";
}

std::string OpenNi2Camera::deviceString() const {
  if (!s_) return name();
  const std::string model = s_->info.vendor.empty() ? s_->info.name : s_->info.vendor + " " + s_->info.name;
  return options_.oni_file.empty() ? model + " (" + s_->info.uri + ")" : model + " (recording " + options_.oni_file + ")";
}

const OpenNi2DeviceInfo& OpenNi2Camera::info() const {
  if (!s_) throw Error(name() + ": not open");
  return s_->info;
}

void OpenNi2Camera::open() {
  startOpenNi2();
  auto s = std::make_unique<Streams>();
  if (!options_.oni_file.empty()) {
    if (!std::ifstream(options_.oni_file).good()) throw Error(options_.oni_file + ": no such .oni recording");
    // libOniFile trusts the file and crashes on a corrupt one: walked and checked first.
    checkOniRecording(options_.oni_file);
    if (s->device.open(options_.oni_file.c_str()) != openni::STATUS_OK)
      throw Error(options_.oni_file + ": not a readable .oni recording (OpenNI2: " +
                  openNiError() + ")");
  } else {
    const std::vector<std::string> present = presentUris();
    if (present.empty())
      throw Error("no OpenNI2 device found (is it plugged in and readable by this user? OpenNI2's drivers folder: " +
                  driverFolders() + ")");
    const std::string uri = options_.uri.empty() ? firstOpenNi2Device(present) : options_.uri;
    if (s->device.open(uri.c_str()) != openni::STATUS_OK) {
      // A URI no driver listed may still be one a driver answers when asked (OpenNI2 asks each one
      // first); refused by all, it is not there.
      if (!options_.uri.empty() && std::find(present.begin(), present.end(), options_.uri) == present.end()) {
        std::string list;
        for (const auto& p : present) list += (list.empty() ? "" : ", ") + p;
        throw Error("OpenNI2 device '" + options_.uri + "' not found; present: " + list);
      }
      throw Error(name() + ": could not open it (OpenNI2: " + openNiError() + ")");
    }
  }
  const openni::DeviceInfo& di = s->device.getDeviceInfo();
  s->info.uri = options_.oni_file.empty() ? di.getUri() : options_.oni_file;
  s->info.vendor = di.getVendor();
  s->info.name = di.getName();
  s->info.usb_vendor_id = di.getUsbVendorId();
  s->info.usb_product_id = di.getUsbProductId();
  if (!s->device.hasSensor(openni::SENSOR_DEPTH)) throw Error(name() + ": the device has no depth stream");
  if (s->depth.create(s->device, openni::SENSOR_DEPTH) != openni::STATUS_OK)
    throw Error(name() + ": could not create its depth stream (OpenNI2: " + openNiError() + ")");
  const auto& modes = s->depth.getSensorInfo().getSupportedVideoModes();
  for (int i = 0; i < modes.getSize(); ++i) s->info.depth_modes.push_back(modeOf(modes[i]));
  if (!s->device.isFile()) chooseDepthMode(s->depth);
  const openni::VideoMode mode = s->depth.getVideoMode();
  s->depth_unit_m = depthUnitMetres(mode.getPixelFormat());
  if (s->depth_unit_m == 0)
    throw Error(name() + ": its depth stream gives " + pixelFormatName(mode.getPixelFormat()) +
                ", not depth in 1 mm or 100 um units");
  s->info.depth_mode = modeOf(mode);

  // Colour (depth registered to it where supported), else IR: PrimeSense-class devices stream one or
  // the other beside depth, not both.
  if (options_.colour && s->device.hasSensor(openni::SENSOR_COLOR) &&
      s->colour.create(s->device, openni::SENSOR_COLOR) == openni::STATUS_OK) {
    const bool sized = s->device.isFile() ? s->colour.getVideoMode().getPixelFormat() == openni::PIXEL_FORMAT_RGB888
                                          : chooseColourMode(s->colour, mode.getResolutionX(), mode.getResolutionY());
    if (sized && s->colour.start() == openni::STATUS_OK) s->has_colour = true;
    else s->colour.destroy();
  }
  s->info.has_colour = s->device.hasSensor(openni::SENSOR_COLOR);
  s->info.has_ir = s->device.hasSensor(openni::SENSOR_IR);
  s->info.registration = s->device.isImageRegistrationModeSupported(openni::IMAGE_REGISTRATION_DEPTH_TO_COLOR);
  bool registered = false;
  if (s->has_colour && !s->device.isFile() && s->info.registration)
    registered = s->device.setImageRegistrationMode(openni::IMAGE_REGISTRATION_DEPTH_TO_COLOR) == openni::STATUS_OK;
  if (s->has_colour) s->device.setDepthColorSyncEnabled(true);
  if (!s->has_colour && options_.ir && s->info.has_ir && s->ir.create(s->device, openni::SENSOR_IR) == openni::STATUS_OK) {
    if (s->ir.getVideoMode().getPixelFormat() == openni::PIXEL_FORMAT_GRAY16 && s->ir.start() == openni::STATUS_OK)
      s->has_ir = true;
    else s->ir.destroy();
  }
  if (s->depth.start() != openni::STATUS_OK)
    throw Error(name() + ": could not start its depth stream (OpenNI2: " + openNiError() + ")");

  // Registered depth lies in the colour camera's image: its field of view is the one that holds.
  openni::VideoStream& seen = registered ? s->colour : s->depth;
  s->info.hfov_deg = seen.getHorizontalFieldOfView() * 180 / kPi;
  s->info.vfov_deg = seen.getVerticalFieldOfView() * 180 / kPi;
  try {
    s->info.intrinsics = intrinsicsFromFieldOfView(seen.getHorizontalFieldOfView(), seen.getVerticalFieldOfView(),
                                                   mode.getResolutionX(), mode.getResolutionY());
  } catch (const Error& e) {
    throw Error(name() + ": " + e.what());
  }

  if (openni::PlaybackControl* playback = s->device.getPlaybackControl()) {
    playback->setRepeatEnabled(options_.loop);
    if (options_.playback_fps > 0 && mode.getFps() > 0)
      playback->setSpeed(static_cast<float>(options_.playback_fps / mode.getFps()));
    s->frames_in_file = playback->getNumberOfFrames(s->depth);
  }
  s->registered = registered;
  s_ = std::move(s);
}

void OpenNi2Camera::close() { s_.reset(); }

TofFrame OpenNi2Camera::acquireOnce() {
  openni::VideoStream* streams[] = {&s_->depth};
  int ready = -1;
  if (openni::OpenNI::waitForAnyStream(streams, 1, &ready, options_.timeout_ms) != openni::STATUS_OK)
    throw Error("no depth frame within " + std::to_string(options_.timeout_ms) + " ms");
  openni::VideoFrameRef depth;
  if (s_->depth.readFrame(&depth) != openni::STATUS_OK || !depth.isValid())
    throw Error(std::string("reading a depth frame failed (OpenNI2: ") + openNiError() + ")");
  const std::uint32_t w = depth.getWidth(), h = depth.getHeight();
  if (w != static_cast<std::uint32_t>(s_->info.depth_mode.width) || h != static_cast<std::uint32_t>(s_->info.depth_mode.height) ||
      static_cast<std::size_t>(depth.getDataSize()) < static_cast<std::size_t>(depth.getStrideInBytes()) * (h - 1) + w * 2)
    throw Error("corrupt depth frame: " + std::to_string(w) + " × " + std::to_string(h) + ", " +
                std::to_string(depth.getDataSize()) + " bytes");
  TofFrame f = depthCameraFrame(static_cast<const std::uint16_t*>(depth.getData()), w, h,
                                static_cast<std::size_t>(depth.getStrideInBytes()), s_->info.intrinsics, s_->depth_unit_m);
  f.timestamp = std::chrono::system_clock::now();
  f.depth_camera->device_timestamp_us = depth.getTimestamp();
  f.depth_camera->registered = s_->registered;
  f.device = deviceString();
  f.sequence = ++sequence_;
  f.settings = settings_;

  // Colour and IR arrive beside depth (synchronised where the device can); a late one is left out.
  auto side = [&](openni::VideoStream& stream, openni::VideoFrameRef& frame) {
    openni::VideoStream* one[] = {&stream};
    int r = -1;
    return openni::OpenNI::waitForAnyStream(one, 1, &r, 100) == openni::STATUS_OK &&
           stream.readFrame(&frame) == openni::STATUS_OK && frame.isValid();
  };
  // A side frame is used only when its buffer holds all its rows (as the depth frame is checked above).
  auto whole = [](const openni::VideoFrameRef& frame, int bytes_per_pixel) {
    return frame.getWidth() > 0 && frame.getHeight() > 0 &&
           static_cast<std::size_t>(frame.getDataSize()) >=
               static_cast<std::size_t>(frame.getStrideInBytes()) * (frame.getHeight() - 1) +
                   static_cast<std::size_t>(frame.getWidth()) * bytes_per_pixel;
  };
  openni::VideoFrameRef extra;
  if (s_->has_colour && side(s_->colour, extra) && extra.getVideoMode().getPixelFormat() == openni::PIXEL_FORMAT_RGB888 &&
      whole(extra, 3)) {
    const std::uint32_t cw = extra.getWidth(), ch = extra.getHeight();
    auto& d = *f.depth_camera;
    d.colour_width = cw;
    d.colour_height = ch;
    d.colour.resize(static_cast<std::size_t>(cw) * ch * 3);
    const auto* src = static_cast<const std::uint8_t*>(extra.getData());
    for (std::uint32_t v = 0; v < ch; ++v)
      std::memcpy(&d.colour[static_cast<std::size_t>(v) * cw * 3], src + v * extra.getStrideInBytes(), cw * 3);
  }
  if (s_->has_ir && side(s_->ir, extra) && extra.getWidth() == static_cast<int>(w) && extra.getHeight() == static_cast<int>(h) &&
      whole(extra, 2)) {
    const auto* src = static_cast<const std::uint8_t*>(extra.getData());
    f.amplitude.resize(f.distance.size());
    f.cloud.amplitude.resize(f.distance.size());
    for (std::uint32_t v = 0; v < h; ++v) {
      std::memcpy(&f.amplitude[static_cast<std::size_t>(v) * w], src + v * extra.getStrideInBytes(), w * 2);
      for (std::uint32_t u = 0; u < w; ++u)
        f.cloud.amplitude[v * w + u] = f.amplitude[v * w + u];
    }
  }
  ++s_->frames_read;
  return f;
}

TofFrame OpenNi2Camera::acquire() {
  // The end of a recording played once is not a device lost: no reopening.
  if (s_ && !options_.loop && s_->frames_in_file > 0 && s_->frames_read >= s_->frames_in_file)
    throw EndOfRecording(options_.oni_file + ": end of the recording after its " +
                         std::to_string(s_->frames_in_file) + " frames");
  return withReopening(
      name(), RetryPolicy{options_.reconnect_attempts, options_.backoff_initial_ms}, options_.log,
      [&] {
        if (!s_) throw Error("not open");  // the last reopen failed
        return acquireOnce();
      },
      [&] {
        close();
        open();
        ++reconnects_;
      });
}

}  // namespace keyturn::drivers
