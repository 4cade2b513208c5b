#include "sim_device.h"

#include <sys/stat.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <exception>
#include <iomanip>
#include <sstream>

#include "keyturn/sim/mesh.h"
#include "sim_properties.h"
#include "sim_stream.h"

namespace keyturn::sim::openni2 {

namespace {
// The PS1080's 640 × 480 modes, at the simulator's one resolution.
constexpr int kFps = 30;

template <typename T>
OniStatus putValue(void* data, int* size, const T& value) {
  if (!data || !size || *size < static_cast<int>(sizeof(T))) return ONI_STATUS_BAD_PARAMETER;
  std::memcpy(data, &value, sizeof(T));
  *size = sizeof(T);
  return ONI_STATUS_OK;
}

OniStatus putString(void* data, int* size, const std::string& s) {
  if (!data || !size || *size < static_cast<int>(s.size()) + 1) return ONI_STATUS_BAD_PARAMETER;
  std::memcpy(data, s.c_str(), s.size() + 1);
  *size = static_cast<int>(s.size()) + 1;
  return ONI_STATUS_OK;
}
}  // namespace

std::string sceneKey(const MesaSrSimConfig& config) {
  std::ostringstream key;
  key << config.mesh << '\n' << std::setprecision(17) << config.scale;
  struct stat st;
  if (config.mesh.rfind("builtin:", 0) != 0 && ::stat(config.mesh.c_str(), &st) == 0)
    key << '\n' << st.st_size << '\n' << st.st_mtim.tv_sec << '.' << st.st_mtim.tv_nsec;
  return key.str();
}

SimDevice::SimDevice(const MesaSrSimConfig& config, StructuredLightScenes& scenes)
    : config_(config), scenes_(scenes), opened_(std::chrono::steady_clock::now()) {
  renderer_ = scenes_.take(sceneKey(config_), [this] {
    return std::make_unique<StructuredLightRenderer>(scaledMesh(loadMeshOrBuiltin(config_.mesh), config_.scale));
  });
  distance_ = config_.distance > 0 ? config_.distance : renderer_->operatorDistance();
  const int w = intrinsics().width, h = intrinsics().height;
  depth_modes_ = {{ONI_PIXEL_FORMAT_DEPTH_1_MM, w, h, kFps}, {ONI_PIXEL_FORMAT_DEPTH_100_UM, w, h, kFps}};
  color_modes_ = {{ONI_PIXEL_FORMAT_RGB888, w, h, kFps}};
  ir_modes_ = {{ONI_PIXEL_FORMAT_GRAY16, w, h, kFps}};
  sensors_ = {{ONI_SENSOR_DEPTH, static_cast<int>(depth_modes_.size()), depth_modes_.data()},
              {ONI_SENSOR_COLOR, static_cast<int>(color_modes_.size()), color_modes_.data()},
              {ONI_SENSOR_IR, static_cast<int>(ir_modes_.size()), ir_modes_.data()}};
  // The scene is cast by the open, not the first frame: opening may take its time, a frame may not.
  // It is cast on the frame thread, waited for here: Embree's task scheduler (TBB) then works on a
  // thread that ends with the device. Cast on the application's thread, TBB's workers outlived the
  // driver's unloading at OpenNI::shutdown and crashed there (ASan: SEGV in unmapped code).
  thread_ = std::thread([this] { run(); });
  std::exception_ptr failed;
  {
    std::unique_lock<std::mutex> lock(mutex_);
    wake_.wait(lock, [this] { return prepared_; });
    failed = prepare_failed_;
  }
  if (failed) {
    thread_.join();
    std::rethrow_exception(failed);
  }
}

SimDevice::~SimDevice() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

OniStatus SimDevice::getSensorInfoList(OniSensorInfo** infos, int* count) {
  *infos = sensors_.data();
  *count = static_cast<int>(sensors_.size());
  return ONI_STATUS_OK;
}

const OniSensorInfo* SimDevice::sensor(OniSensorType type) const {
  for (const auto& s : sensors_)
    if (s.sensorType == type) return &s;
  return nullptr;
}

oni::driver::StreamBase* SimDevice::createStream(OniSensorType type) {
  return sensor(type) ? new SimStream(*this, type) : nullptr;
}

void SimDevice::destroyStream(oni::driver::StreamBase* stream) {
  auto* s = static_cast<SimStream*>(stream);
  streamStopped(s);  // OpenNI stops a stream before destroying it; this makes sure
  delete s;
}

void SimDevice::streamStarted(SimStream* s) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (std::find(active_.begin(), active_.end(), s) == active_.end()) active_.push_back(s);
  wake_.notify_all();
}

void SimDevice::streamStopped(SimStream* s) {
  std::lock_guard<std::mutex> lock(mutex_);  // waits out a delivery in progress
  active_.erase(std::remove(active_.begin(), active_.end(), s), active_.end());
}

OniBool SimDevice::isImageRegistrationModeSupported(OniImageRegistrationMode mode) {
  return mode == ONI_IMAGE_REGISTRATION_OFF || mode == ONI_IMAGE_REGISTRATION_DEPTH_TO_COLOR;
}

OniBool SimDevice::isPropertySupported(int id) {
  switch (id) {
    case ONI_DEVICE_PROPERTY_FIRMWARE_VERSION:
    case ONI_DEVICE_PROPERTY_DRIVER_VERSION:
    case ONI_DEVICE_PROPERTY_HARDWARE_VERSION:
    case ONI_DEVICE_PROPERTY_SERIAL_NUMBER:
    case ONI_DEVICE_PROPERTY_IMAGE_REGISTRATION:
    case kScenesBuiltProperty:
    case kSceneCastsProperty:
      return TRUE;
    default:
      return FALSE;
  }
}

OniStatus SimDevice::getProperty(int id, void* data, int* size) {
  switch (id) {
    case ONI_DEVICE_PROPERTY_FIRMWARE_VERSION:
      return putString(data, size, "keyturn-sim 1");
    case ONI_DEVICE_PROPERTY_DRIVER_VERSION:
      return putValue(data, size, OniVersion{1, 0, 0, 0});
    case ONI_DEVICE_PROPERTY_HARDWARE_VERSION:
      return putValue(data, size, OniHardwareVersion{0});
    case ONI_DEVICE_PROPERTY_SERIAL_NUMBER:
      return putString(data, size, std::to_string(config_.serial));
    case ONI_DEVICE_PROPERTY_IMAGE_REGISTRATION:
      return putValue(data, size, registration_);
    case kScenesBuiltProperty:
      return putValue(data, size, static_cast<int>(scenes_.built()));
    case kSceneCastsProperty: {
      std::lock_guard<std::mutex> lock(mutex_);  // the frame thread casts with mutex_ released: see run()
      return putValue(data, size, casts_);
    }
    default:
      return ONI_STATUS_NOT_SUPPORTED;
  }
}

OniStatus SimDevice::setProperty(int id, const void* data, int size) {
  if (id != ONI_DEVICE_PROPERTY_IMAGE_REGISTRATION) return ONI_STATUS_NOT_SUPPORTED;
  if (!data || size != sizeof(OniImageRegistrationMode)) return ONI_STATUS_BAD_PARAMETER;
  OniImageRegistrationMode mode;
  std::memcpy(&mode, data, sizeof mode);
  if (!isImageRegistrationModeSupported(mode)) return ONI_STATUS_NOT_SUPPORTED;
  // Nothing to warp: colour is already rendered from the depth camera's viewpoint.
  registration_ = mode;
  return ONI_STATUS_OK;
}

bool unplugged(const MesaSrSimConfig& config) {
  struct stat st;
  return !config.unplug_file.empty() && ::stat(config.unplug_file.c_str(), &st) == 0;
}

SceneView SimDevice::view() const {
  SceneView v;
  v.distance = distance_;
  v.elevation_deg = config_.elevation;
  v.roll_deg = config_.roll;
  v.turntable_deg =
      config_.world.empty() ? config_.turntable_deg : readWorldTurntable(config_.world, config_.turntable_deg);
  return v;
}

StructuredLightFrame SimDevice::renderFrame() {
  SceneView v = view();
  // One noise draw per angle, whichever frame a capture takes; else one per frame, repeatable.
  v.seed = config_.noise_per_pose ? config_.poseNoiseSeed(v.turntable_deg)
                                  : config_.seed * 1000003ULL + static_cast<std::uint64_t>(frames_);
  return renderer_->render(v);
}

void SimDevice::run() {
  const double rate = config_.frame_rate > 0 ? config_.frame_rate : kFps;
  const auto period = std::chrono::duration_cast<std::chrono::steady_clock::duration>(
      std::chrono::duration<double>(1.0 / rate));
  std::exception_ptr failed;
  try {
    renderer_->prepare(view());
  } catch (...) {
    failed = std::current_exception();
  }
  std::unique_lock<std::mutex> lock(mutex_);
  prepared_ = true;
  prepare_failed_ = failed;
  casts_ = static_cast<int>(renderer_->casts());
  wake_.notify_all();
  if (failed) return;  // the constructor rethrows it
  auto next = std::chrono::steady_clock::now();
  while (!stop_) {
    if (active_.empty()) {
      wake_.wait(lock, [this] { return stop_ || !active_.empty(); });
      next = std::chrono::steady_clock::now();
      continue;
    }
    if (wake_.wait_until(lock, next, [this] { return stop_; })) break;
    // The frame's instant, its timestamp: a camera stamps the exposure, not the delivery.
    const auto slot = next;
    // A slow render (the turntable moved: the scene is cast again) delays the
    // next frame rather than bunching frames up after it.
    next = std::max(next + period, std::chrono::steady_clock::now());
    ++periods_;
    const auto& f = config_.faults;
    if (disconnected_ || unplugged(config_)) continue;  // the cable is out: no frames
    if (f.disconnect_after > 0 && frames_ >= f.disconnect_after) {
      disconnected_ = true;
      continue;
    }
    if (f.timeout_every > 0 && periods_ % f.timeout_every == 0) continue;  // a dropped frame
    lock.unlock();
    StructuredLightFrame frame;
    bool rendered = true;
    try {
      frame = renderFrame();
    } catch (const std::exception& e) {
      std::fprintf(stderr, "keyturn-sim OpenNI2 driver: %s\n", e.what());
      rendered = false;
    }
    const auto timestamp =
        static_cast<std::uint64_t>(std::chrono::duration_cast<std::chrono::microseconds>(slot - opened_).count());
    lock.lock();
    casts_ = static_cast<int>(renderer_->casts());  // read here, by the thread that casts
    if (!rendered) continue;
    ++frames_;
    for (SimStream* s : active_) s->deliver(frame, frames_, timestamp);
  }
}

}  // namespace keyturn::sim::openni2
