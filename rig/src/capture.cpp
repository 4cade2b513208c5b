#include "keyturn/rig/capture.h"

#include <Eigen/Geometry>
#include <chrono>
#include <cmath>
#include <thread>

#include "keyturn/core/error.h"
#include "keyturn/rig/captured_views.h"

namespace keyturn::rig {
namespace {

using Clock = std::chrono::steady_clock;

double angleDiff(double a, double b) {
  double d = std::fmod(a - b, 360.0);
  if (d > 180) d -= 360;
  if (d < -180) d += 360;
  return std::abs(d);
}

// Waits until the pose has been within tolerance of the target, and not moving,
// for the settle time. Returns the last pose read.
drivers::Pose waitStable(drivers::PoseSource& pose, double target, const CaptureOptions& o) {
  const auto deadline = Clock::now() + std::chrono::duration<double>(o.move_timeout_s);
  std::optional<Clock::time_point> stable_since;
  drivers::Pose p;
  for (;;) {
    p = pose.read();
    // Not moving is not yet settled: a drive reports "in position" only after its settling window
    // (an angle read while settling carries the encoder's jitter, and was written as the view's).
    const bool ok = !p.moving && p.in_position && angleDiff(p.turntable_deg, target) <= o.tolerance_deg;
    if (!ok) stable_since.reset();
    else if (!stable_since) stable_since = Clock::now();
    if (stable_since && Clock::now() - *stable_since >= std::chrono::duration<double>(o.settle_s)) return p;
    if (Clock::now() > deadline)
      throw Error(pose.describe() + ": not stable within " + std::to_string(o.tolerance_deg) + "° of " +
                  std::to_string(target) + "° after " + std::to_string(o.move_timeout_s) + " s (at " +
                  std::to_string(p.turntable_deg) + "°, " + (p.moving ? "moving" : p.in_position ? "still" : "not in position") +
                  ")");
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}

}  // namespace

std::vector<double> sequenceAngles(const CaptureOptions& o) {
  if (!(o.step_deg > 0)) throw Error("capture: the step must be positive");
  std::vector<double> out;
  for (int k = 0; k * o.step_deg < o.range_deg - 1e-9; ++k) out.push_back(std::fmod(o.start_deg + k * o.step_deg, 360.0));
  return out;
}

CaptureReport runCapture(drivers::TofCamera& camera, drivers::PoseSource& pose, dataset::Dataset& dataset,
                         const CaptureOptions& o, const std::function<void(const CaptureProgress&)>& progress) {
  CaptureReport rep;
  const auto angles = sequenceAngles(o);
  CaptureProgress prog;
  prog.total = angles.size();
  for (double angle : angles) {
    prog.frame = nullptr;
    prog.record = nullptr;
    if (o.stop && *o.stop) {
      rep.stopped = true;
      break;
    }
    const dataset::ViewKey key{o.cls, o.instance, o.elevation_label, angle};
    prog.angle_deg = angle;
    if (dataset.has(key)) {
      ++rep.skipped;
      ++prog.skipped;
      if (progress) progress(prog);
      continue;
    }
    int redos = 0;
    for (;;) {
      if (pose.canMove()) pose.moveTo(angle);
      const drivers::Pose before = waitStable(pose, angle, o);
      for (int i = 0; i < o.discard_frames; ++i) camera.acquire();
      std::vector<drivers::TofFrame> frames;
      for (int i = 0; i < o.frames; ++i) frames.push_back(camera.acquire());
      const drivers::Pose after = pose.read();
      // The table moved during the exposure: this view would be blurred or mislabelled.
      if (after.moving || !after.in_position || angleDiff(after.turntable_deg, before.turntable_deg) > o.tolerance_deg) {
        if (++redos > o.max_redos)
          throw Error(pose.describe() + ": the pose kept moving during acquisition at " + std::to_string(angle) + "°");
        continue;
      }
      dataset::ViewMetadata meta;
      meta.elevation_deg = o.elevation_deg;
      meta.measured_deg = 0.5 * (before.turntable_deg + after.turntable_deg);
      if (std::abs(before.turntable_deg - after.turntable_deg) > 180) meta.measured_deg = before.turntable_deg;
      if (o.camera_from_turntable_zero) {
        Eigen::Matrix4d rz = Eigen::Matrix4d::Identity();
        rz.topLeftCorner<3, 3>() =
            Eigen::AngleAxisd(meta.measured_deg * M_PI / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
        meta.camera_from_turntable = *o.camera_from_turntable_zero * rz;
      }
      meta.pose_source = pose.describe();
      meta.frames_discarded = o.discard_frames;
      meta.frames_taken = o.frames;
      meta.redos = redos;
      const drivers::TofFrame median = drivers::medianFrame(frames);
      const dataset::ViewRecord record = writeFrameView(dataset, key, meta, median);
      rep.redos += static_cast<std::size_t>(redos);
      ++rep.written;
      ++prog.done;
      prog.frame = &median;
      prog.record = &record;
      if (progress) progress(prog);
      break;
    }
  }
  return rep;
}

}  // namespace keyturn::rig
