#pragma once
// A dataset (captured, simulated or imported) replayed as a device, the way
// librealsense's playback device stands in for a camera: a TofCamera that
// delivers the views in manifest order at the recorded or a chosen rate,
// looping or not, and a PoseSource that reports the pose recorded with the
// frame being shown. Both share one Recording (the timeline).
//
// A move command seeks: the next view (from the one shown, wrapping round)
// recorded at the commanded angle nearest the target, and playback holds
// there, as a turntable stays where it was sent; so `keyturn capture` runs
// on a recording unchanged and writes the views it holds.
#include <Eigen/Core>
#include <chrono>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "keyturn/core/error.h"
#include "keyturn/drivers/pose_source.h"
#include "keyturn/drivers/tof_camera.h"
#include "keyturn/dataset/dataset.h"

namespace keyturn::rig {

// The end of a recording that does not loop (tof_camera.h: .oni files end the same way).
using EndOfRecording = drivers::EndOfRecording;

struct PlaybackOptions {
  double rate_fps = 0;  // 0: the recorded rate (the median interval between views' capture times)
  bool loop = true;     // false: acquire after the last view throws "end of the recording"
};

class Recording {
 public:
  // Throws keyturn::Error naming the manifest: no dataset, no views, no recorded rate (and none given).
  Recording(std::string root, PlaybackOptions options);

  const std::string& root() const { return root_; }
  const std::vector<dataset::ViewRecord>& views() const { return views_; }
  double frameRate() const { return rate_fps_; }
  bool looping() const { return options_.loop; }
  // Camera ← turntable at 0°, from the first view's sidecar (none when the rig was not calibrated).
  const std::optional<Eigen::Matrix4d>& cameraFromTurntable() const { return camera_from_turntable_; }
  std::string describe() const;  // "recording DATASET (N views, R frames/s, looping)"

  // The camera's side: waits until the next frame is due, loads it and makes it the one shown.
  // Throws keyturn::Error naming the view file that is gone or unreadable, and EndOfRecording
  // naming the manifest at the end of a recording that does not loop (until rewound).
  drivers::TofFrame next();
  bool ended() const;
  void rewind();  // from the first view again, playing (not held)
  // The pose source's side: the pose recorded with the frame shown (the first view's before any).
  drivers::Pose pose() const;
  void seek(double turntable_deg);  // to the nearest recorded angle, and hold
  void hold();                      // keep showing the frame shown
  std::size_t shown() const;        // the index of the frame shown
  std::uint64_t delivered() const;  // frames delivered so far
  drivers::TofSettings settings() const;  // recorded with the frame shown

 private:
  drivers::TofFrame load(std::size_t index) const;

  std::string root_;
  PlaybackOptions options_;
  std::vector<dataset::ViewRecord> views_;
  double rate_fps_ = 0;
  std::optional<Eigen::Matrix4d> camera_from_turntable_;

  mutable std::mutex mutex_;
  std::size_t shown_ = 0;
  std::uint64_t delivered_ = 0;
  bool held_ = false, ended_ = false;
  drivers::TofSettings settings_;
  std::chrono::steady_clock::time_point last_due_;
};

class PlaybackCamera final : public drivers::TofCamera {
 public:
  explicit PlaybackCamera(std::shared_ptr<Recording> recording) : recording_(std::move(recording)) {}
  // A recording keeps the settings it was made with: configure changes nothing, settings() says what they were.
  void configure(const drivers::TofSettings&) override {}
  drivers::TofSettings settings() const override { return recording_->settings(); }
  drivers::TofFrame acquire() override { return recording_->next(); }
  std::string deviceString() const override { return recording_->describe(); }
  std::uint32_t serial() const override;
  Recording& recording() { return *recording_; }

 private:
  std::shared_ptr<Recording> recording_;
};

class PlaybackPose final : public drivers::PoseSource {
 public:
  explicit PlaybackPose(std::shared_ptr<Recording> recording) : recording_(std::move(recording)) {}
  drivers::Pose read() override { return recording_->pose(); }
  bool canMove() const override { return true; }
  void moveTo(double deg) override { recording_->seek(deg); }
  void home() override { recording_->seek(0); }
  void stop() override { recording_->hold(); }
  std::string describe() const override { return "playback of " + recording_->root(); }

 private:
  std::shared_ptr<Recording> recording_;
};

}  // namespace keyturn::rig
