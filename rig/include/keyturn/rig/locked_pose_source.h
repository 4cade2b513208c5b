#pragma once
// One pose source used from several threads (a live readout polling it while a
// capture sequence commands it): every call holds the device's lock, so the
// requests on the wire never interleave.
#include <memory>
#include <mutex>

#include "keyturn/drivers/pose_source.h"

namespace keyturn::rig {

class LockedPoseSource final : public drivers::PoseSource {
 public:
  explicit LockedPoseSource(std::unique_ptr<drivers::PoseSource> source) : source_(std::move(source)) {}
  drivers::Pose read() override {
    std::lock_guard<std::mutex> l(mutex_);
    return source_->read();
  }
  bool canMove() const override { return source_->canMove(); }
  void moveTo(double deg) override {
    std::lock_guard<std::mutex> l(mutex_);
    source_->moveTo(deg);
  }
  void home() override {
    std::lock_guard<std::mutex> l(mutex_);
    source_->home();
  }
  void stop() override {
    std::lock_guard<std::mutex> l(mutex_);
    source_->stop();
  }
  std::string describe() const override { return source_->describe(); }

 private:
  std::unique_ptr<drivers::PoseSource> source_;
  std::mutex mutex_;
};

}  // namespace keyturn::rig
