#pragma once
// A capture sequence at one camera elevation: for angle = start, start + step, …
// command (or wait for) the pose, wait until it is stable within a tolerance
// for a settle time, discard N frames, take M (per-pixel median), read the pose
// again and redo the view if it moved, then write the view. Views already in
// the dataset are skipped, so re-running an interrupted capture resumes it.
#include <Eigen/Core>
#include <atomic>
#include <functional>
#include <optional>
#include <string>

#include "keyturn/drivers/pose_source.h"
#include "keyturn/drivers/tof_camera.h"
#include "keyturn/dataset/dataset.h"

namespace keyturn::rig {

struct CaptureOptions {
  std::string cls, instance;
  std::string elevation_label;
  double elevation_deg = 30.0;
  double start_deg = 0.0, step_deg = 5.0, range_deg = 360.0;  // views at start + k·step, k·step < range
  double tolerance_deg = 0.1;
  double settle_s = 0.2;        // the pose must stay within tolerance this long
  double move_timeout_s = 30.0;
  int discard_frames = 1;
  int frames = 1;
  int max_redos = 3;
  // Camera-from-turntable at 0°; each view gets it composed with its rotation.
  std::optional<Eigen::Matrix4d> camera_from_turntable_zero;
  std::atomic<bool>* stop = nullptr;  // set (e.g. by Ctrl-C) to stop after the current view
};

struct CaptureProgress {
  std::size_t done = 0, skipped = 0, total = 0;
  double angle_deg = 0;
  // The view just written (valid during the callback only); null for a skipped view.
  const drivers::TofFrame* frame = nullptr;
  const dataset::ViewRecord* record = nullptr;
};

struct CaptureReport {
  std::size_t written = 0, skipped = 0, redos = 0;
  bool stopped = false;
};

std::vector<double> sequenceAngles(const CaptureOptions& o);

CaptureReport runCapture(drivers::TofCamera& camera, drivers::PoseSource& pose, dataset::Dataset& dataset,
                         const CaptureOptions& options,
                         const std::function<void(const CaptureProgress&)>& progress = {});

}  // namespace keyturn::rig
