#pragma once
// A camera's frames as a dataset's views and back: a frame written as a view (its files,
// frame_files.h, and its camera recorded in the sidecar), and the camera a view was taken with
// read back as the camera's settings, for playback to take the view again.
#include <string>

#include "keyturn/dataset/dataset.h"
#include "keyturn/drivers/tof_camera.h"

namespace keyturn::rig {

// The frame's files (writeFrameFiles), its sidecar and its manifest row, durably; returns the record.
// Throws keyturn::Error for a view already in the dataset.
dataset::ViewRecord writeFrameView(dataset::Dataset& into, const dataset::ViewKey& key,
                                   const dataset::ViewMetadata& meta, const drivers::TofFrame& frame);

// The camera a view was taken with (its device string, serial and the settings its sidecar keeps:
// modulation, integration time, auto exposure, amplitude threshold, acquire mode). A view imported
// from another tool (keyturn import) records none: the default settings, and imported set.
struct ViewCamera {
  std::string device;
  std::uint32_t serial = 0;
  drivers::TofSettings settings;
  bool imported = false;  // its captured_at is when it was imported, not taken
};
// Throws keyturn::Error naming the sidecar when it is unreadable or records a frequency the camera lacks.
ViewCamera readViewCamera(const std::string& sidecar_path);

}  // namespace keyturn::rig
