#include "keyturn/rig/dataset_playback.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <sstream>
#include <thread>

#include "keyturn/core/error.h"
#include "keyturn/core/median.h"
#include "keyturn/rig/frame_files.h"
#include "keyturn/dataset/sidecars.h"
#include "keyturn/rig/captured_views.h"
#include "keyturn/dataset/dataset_layout.h"

namespace fs = std::filesystem;

namespace keyturn::rig {
namespace {

using Clock = std::chrono::steady_clock;

// Seconds since the epoch of a manifest's captured_at ("2026-11-22T00:32:35.508Z"); NaN when it is not one.
double capturedAtSeconds(const std::string& iso) {
  std::tm tm{};
  double seconds = 0;
  if (std::sscanf(iso.c_str(), "%4d-%2d-%2dT%2d:%2d:%lfZ", &tm.tm_year, &tm.tm_mon, &tm.tm_mday, &tm.tm_hour,
                  &tm.tm_min, &seconds) != 6)
    return std::nan("");
  tm.tm_year -= 1900;
  tm.tm_mon -= 1;
  return static_cast<double>(::timegm(&tm)) + seconds;
}

// The recorded rate: the median of the positive intervals between consecutive views' capture
// times (a capture paused and resumed, or a second elevation a day later, does not slow it down).
double recordedRate(const std::vector<dataset::ViewRecord>& views) {
  std::vector<double> gaps;
  for (std::size_t i = 1; i < views.size(); ++i) {
    const double d = capturedAtSeconds(views[i].captured_at) - capturedAtSeconds(views[i - 1].captured_at);
    if (std::isfinite(d) && d > 0) gaps.push_back(d);
  }
  if (gaps.empty()) return 0;
  return 1.0 / upperMedian(std::move(gaps));
}

double angleDiff(double a, double b) {
  double d = std::fmod(std::abs(a - b), 360.0);
  return d > 180 ? 360 - d : d;
}

std::string viewName(const dataset::ViewRecord& r) {
  char angle[32];
  std::snprintf(angle, sizeof angle, "%.1f", r.key.commanded_deg);
  return r.key.cls + "/" + r.key.instance + "/e" + r.key.elevation + "/a" + angle;
}

}  // namespace

Recording::Recording(std::string root, PlaybackOptions options) : root_(std::move(root)), options_(options) {
  while (root_.size() > 1 && root_.back() == '/') root_.pop_back();
  const std::string manifest = dataset::manifestPath(root_);
  if (!fs::is_directory(root_)) throw Error(root_ + ": no such dataset to play back");
  if (!fs::is_regular_file(manifest)) throw Error(manifest + ": missing (not a keyturn dataset to play back)");
  views_ = dataset::Dataset::readManifest(root_);
  if (views_.empty()) throw Error(manifest + ": no views to play back");
  if (!(options_.rate_fps >= 0) || !std::isfinite(options_.rate_fps))
    throw Error(root_ + ": playback rate " + std::to_string(options_.rate_fps) + " frames/s is not a rate");
  const std::string sidecar = views_.front().sidecar();
  const ViewCamera first = sidecar.empty() ? ViewCamera() : readViewCamera(root_ + "/" + sidecar);
  if (options_.rate_fps == 0 && first.imported)
    throw Error(manifest + ": imported views (their capture times are the import's) have no recorded rate: choose a playback rate");
  rate_fps_ = options_.rate_fps > 0 ? options_.rate_fps : recordedRate(views_);
  if (!(rate_fps_ > 0))
    throw Error(manifest + ": the views' capture times give no rate (fewer than two distinct): choose a playback rate");
  if (!sidecar.empty()) {
    const std::string path = root_ + "/" + sidecar;
    if (const auto t = dataset::readViewTransform(path)) {
      // Back to the table at 0°: the sidecar's transform is at the view's measured angle.
      Eigen::Matrix4d rz = Eigen::Matrix4d::Identity();
      rz.topLeftCorner<3, 3>() =
          Eigen::AngleAxisd(-views_.front().measured_deg * M_PI / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
      camera_from_turntable_ = *t * rz;
    }
    settings_ = first.settings;
  }
}

std::string Recording::describe() const {
  std::ostringstream s;
  s << "recording " << root_ << " (" << views_.size() << " views, " << rate_fps_ << " frames/s"
    << (options_.loop ? ", looping" : "") << ")";
  return s.str();
}

drivers::TofFrame Recording::load(std::size_t index) const {
  const dataset::ViewRecord& r = views_[index];
  // Every file the row lists, not only those read: a view with a file gone is not the recorded one.
  for (const auto& f : r.files)
    if (!fs::exists(root_ + "/" + f)) throw Error(root_ + "/" + f + ": missing (view " + viewName(r) + " of the recording)");
  const std::string pcd = r.pcd();
  if (pcd.empty()) throw Error(dataset::manifestPath(root_) + ": view " + viewName(r) + " lists no point cloud");
  ViewCamera camera;
  if (!r.sidecar().empty()) camera = readViewCamera(root_ + "/" + r.sidecar());
  drivers::TofFrame f =
      readFrameFiles(root_ + "/" + pcd, drivers::nonAmbiguousRange(camera.settings.modulation_frequency));
  f.settings = camera.settings;
  f.device = camera.device;
  f.serial = camera.serial;
  return f;
}

drivers::TofFrame Recording::next() {
  // Paced outside the lock, so the pose stays readable (and seekable) while the camera waits.
  Clock::time_point due;
  {
    std::lock_guard<std::mutex> l(mutex_);
    const auto interval = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / rate_fps_));
    const auto now = Clock::now();
    due = delivered_ == 0 ? now : last_due_ + interval;
    if (due + interval < now) due = now;  // a slow reader is not paid back with a burst
    last_due_ = due;
  }
  std::this_thread::sleep_until(due);
  std::lock_guard<std::mutex> l(mutex_);
  std::size_t index = shown_;
  if (!held_ && delivered_ > 0) {
    index = shown_ + 1;
    if (index == views_.size()) {
      if (!options_.loop) {
        ended_ = true;
        throw EndOfRecording(dataset::manifestPath(root_) + ": end of the recording after its " + std::to_string(views_.size()) +
                    " views (not looping)");
      }
      index = 0;
    }
  }
  drivers::TofFrame f = load(index);
  shown_ = index;
  settings_ = f.settings;
  f.sequence = ++delivered_;
  f.timestamp = std::chrono::system_clock::now();  // when shown, as a live camera stamps its frames
  return f;
}

drivers::Pose Recording::pose() const {
  std::lock_guard<std::mutex> l(mutex_);
  drivers::Pose p;
  p.turntable_deg = views_[shown_].measured_deg;
  p.moving = false;
  p.in_position = true;
  p.stamp = std::chrono::system_clock::now();
  return p;
}

void Recording::seek(double deg) {
  std::lock_guard<std::mutex> l(mutex_);
  // From the view shown onwards, so a dataset of several sequences stays in the one being played.
  std::size_t best = shown_;
  double best_diff = 1e9;
  for (std::size_t k = 0; k < views_.size(); ++k) {
    const std::size_t i = (shown_ + k) % views_.size();
    const double d = angleDiff(views_[i].key.commanded_deg, deg);
    if (d < best_diff - 1e-9) {
      best_diff = d;
      best = i;
    }
  }
  shown_ = best;
  held_ = true;
  ended_ = false;  // a recording that ended plays again from where it was sent
}

bool Recording::ended() const {
  std::lock_guard<std::mutex> l(mutex_);
  return ended_;
}

void Recording::rewind() {
  std::lock_guard<std::mutex> l(mutex_);
  shown_ = 0;
  delivered_ = 0;
  held_ = ended_ = false;
}

void Recording::hold() {
  std::lock_guard<std::mutex> l(mutex_);
  held_ = true;
}

std::size_t Recording::shown() const {
  std::lock_guard<std::mutex> l(mutex_);
  return shown_;
}

std::uint64_t Recording::delivered() const {
  std::lock_guard<std::mutex> l(mutex_);
  return delivered_;
}

drivers::TofSettings Recording::settings() const {
  std::lock_guard<std::mutex> l(mutex_);
  return settings_;
}

std::uint32_t PlaybackCamera::serial() const {
  // The recording's camera, as its first view's sidecar names it.
  const auto& v = recording_->views().front();
  return v.sidecar().empty() ? 0 : readViewCamera(recording_->root() + "/" + v.sidecar()).serial;
}

}  // namespace keyturn::rig
