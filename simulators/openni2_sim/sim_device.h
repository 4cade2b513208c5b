#pragma once
// The simulated OpenNI2 device: the simulated rig's scene seen by a Kinect-class
// structured-light camera (keyturn/sim/structured_light_view.h), turned by the
// shared simulated turntable (the config's world file). One thread renders a
// frame per period while any stream runs and hands it to every started stream,
// so depth, colour and IR of one instant share a frame index and timestamp.
// The scene is built and cast when the device is opened, or taken already built
// from the driver's kept scenes, so the first frame costs what later ones do (a
// fresh scene's cast took seconds under ASan on a loaded machine: OpenNI2 programs'
// first wait timed out, issue 51).
#include <chrono>
#include <condition_variable>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "keyturn/sim/mesasr_sim_config.h"
#include "keyturn/sim/structured_light_scenes.h"
#include "keyturn/sim/structured_light_view.h"
#include "oni_driver_api.h"

namespace keyturn::sim::openni2 {

class SimStream;

// The simulated cable is out while the configuration's unplug file exists.
bool unplugged(const MesaSrSimConfig& config);

// What names a configuration's scene among kept ones: the mesh (with its file's size and time, so an
// edited file is built again) and its scale.
std::string sceneKey(const MesaSrSimConfig& config);

class SimDevice : public oni::driver::DeviceBase {
 public:
  // Takes its scene from `scenes` (built there if none is kept) and casts it for the configured view.
  // Throws keyturn::Error for a mesh that cannot be loaded.
  SimDevice(const MesaSrSimConfig& config, StructuredLightScenes& scenes);
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
  void run();  // casts the scene, then renders a frame per period while streams run
  SceneView view() const;  // the configured view at the turntable's current angle, without a seed
  StructuredLightFrame renderFrame();

  MesaSrSimConfig config_;
  StructuredLightScenes& scenes_;
  std::shared_ptr<const StructuredLightRenderer> renderer_;  // used by the frame thread once it runs
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
  int casts_ = 0;  // the renderer's casts(), copied under mutex_ for getProperty
  bool prepared_ = false;  // the frame thread has cast the scene (or failed to: prepare_failed_)
  std::exception_ptr prepare_failed_;
  int periods_ = 0;
  std::chrono::steady_clock::time_point opened_;
  std::thread thread_;
};

}  // namespace keyturn::sim::openni2
