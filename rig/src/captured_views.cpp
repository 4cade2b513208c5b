#include "keyturn/rig/captured_views.h"

#include "keyturn/core/error.h"
#include "keyturn/dataset/sidecars.h"
#include "keyturn/rig/frame_files.h"

namespace keyturn::rig {

dataset::ViewRecord writeFrameView(dataset::Dataset& into, const dataset::ViewKey& key,
                                   const dataset::ViewMetadata& meta, const drivers::TofFrame& frame) {
  dataset::SidecarCamera camera;
  camera.device = frame.device;
  camera.serial = frame.serial;
  if (!frame.depth_camera) {  // the SR4000's settings; a depth camera (OpenNI2) has none of them
    camera.modulation_mhz = drivers::modulationMHz(frame.settings.modulation_frequency);
    camera.integration_time = frame.settings.integration_time;
    camera.auto_exposure = frame.settings.auto_exposure.enabled;
    camera.amplitude_threshold = frame.settings.amplitude_threshold;
    camera.acquire_mode = frame.settings.acquire_mode;
  }
  return into.writeCaptured(key, meta, camera,
                            [&frame](const std::string& pcd_path) { return writeFrameFiles(pcd_path, frame); });
}

ViewCamera readViewCamera(const std::string& path) {
  const dataset::SidecarCameraRecord recorded = dataset::readSidecarCamera(path);
  const dataset::SidecarCamera& c = recorded.camera;
  ViewCamera out;
  out.imported = recorded.imported;
  out.device = c.device;
  out.serial = c.serial;
  drivers::TofSettings& s = out.settings;
  try {
    if (c.modulation_mhz) s.modulation_frequency = drivers::modulationIndex(*c.modulation_mhz);
  } catch (const std::exception& e) {
    throw Error(path + ": camera: " + e.what());
  }
  s.integration_time = c.integration_time.value_or(s.integration_time);
  s.auto_exposure.enabled = c.auto_exposure.value_or(s.auto_exposure.enabled);
  s.amplitude_threshold = c.amplitude_threshold.value_or(s.amplitude_threshold);
  s.acquire_mode = c.acquire_mode.value_or(s.acquire_mode);
  return out;
}

}  // namespace keyturn::rig
