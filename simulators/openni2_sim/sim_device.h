#pragma once
// The simulated OpenNI2 device: the simulated rig's scene seen by a Kinect-class
// structured-light camera (keyturn/sim/structured_light_view.h), turned by the
// shared simulated turntable (the config's world file). One thread renders a
// frame per period while any stream runs and hands it to every started stream,
// so depth, colour and IR of one instant share a frame index and timestamp.
#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "keyturn/sim/mesasr_sim_config.h"
#include "keyturn/sim/structured_light_view.h"
#include "oni_driver_api.h"

namespace keyturn::sim::openni2 {

class SimStream;

// The simulated cable is out while the configuration's unplug file exists.
bool unplugged(const MesaSrSimConfig& config);

class SimDevice : public oni::driver::DeviceBase {
 public:
  // Throws keyturn::Error for a mesh that cannot be loaded.
  explicit SimDevice(const MesaSrSimConfig& config);
  ~SimDevice() override;

  OniStatus getSensorInfoList(OniSensorInfo** infos, int* count) override;
  oni::driver::StreamBase* createStream(OniSensorType type) override;
  void destroyStream(oni::driver::StreamBase* stream) override;
  OniStatus setProperty(int id, const void* data, int size) override;
  OniStatus getProperty(int id, void* data, int* size) override;
  OniBool isPropertySupported(int id) override;
  OniBool isImageRegistrationModeSupported(OniImageRegistrationMode mode) override;

  // The video modes a sensor offers (the first is its default), or null.
  const OniSensorInfo* sensor(OniSensorType type) const;
  const Intrinsics& intrinsics() const { return renderer_->intrinsics(); }
  double maxDepth() const { return renderer_->model().max_depth; }
  double baseline() const { return renderer_->model().baseline; }
  void streamStarted(SimStream* s);
  void streamStopped(SimStream* s);

 private:
  void run();
  StructuredLightFrame renderFrame();

  MesaSrSimConfig config_;
  std::unique_ptr<StructuredLightRenderer> renderer_;
  double distance_ = 0.0;
  std::vector<OniVideoMode> depth_modes_, color_modes_, ir_modes_;
  std::vector<OniSensorInfo> sensors_;
  OniImageRegistrationMode registration_ = ONI_IMAGE_REGISTRATION_OFF;

  std::mutex mutex_;  // guards active_ and stop_ with wake_
  std::condition_variable wake_;
  std::vector<SimStream*> active_;
  bool stop_ = false;
  bool disconnected_ = false;  // faults.disconnect_after reached: silent until reopened
  int frames_ = 0;
  int periods_ = 0;
  std::chrono::steady_clock::time_point opened_;
  std::thread thread_;
};

}  // namespace keyturn::sim::openni2
