#include "pose_worker.h"

#include <cmath>

#include "keyturn/rig/locked_pose_source.h"

namespace keyturn::studio {

PoseWorker::PoseWorker(RigFactory& factory) : factory_(factory) {
  poll_ = new QTimer(this);
  poll_->setInterval(100);
  connect(poll_, &QTimer::timeout, this, &PoseWorker::poll);
  reconnect_ = new ReconnectLoop(
      [this] {
        try {
          connectSource();
        } catch (...) {
          source_.reset();
          throw;
        }
      },
      [this] {
        emit recovered(QString::fromStdString(source_->describe()));
        emit opened(QString::fromStdString(source_->describe()), source_->canMove(), source_);
        poll_->start();
      },
      this);
  connect(reconnect_, &ReconnectLoop::logLine, this, &PoseWorker::logLine);
}

PoseWorker::~PoseWorker() = default;

void PoseWorker::connectSource() {
  source_ = std::make_shared<rig::LockedPoseSource>(
      factory_.openPose(*spec_, [this](const std::string& l) { emit logLine(QString::fromStdString(l)); }));
}

void PoseWorker::open(const std::optional<rig::PoseSpec>& spec) {
  close();
  spec_ = spec;
  if (!spec_) return;
  try {
    connectSource();
  } catch (const std::exception& e) {
    source_.reset();
    emit openFailed(QString::fromStdString(spec_->describe() + ": " + e.what()));
    return;
  }
  emit opened(QString::fromStdString(source_->describe()), source_->canMove(), source_);
  poll_->start();
  poll();
}

void PoseWorker::close() {
  poll_->stop();
  reconnect_->stop();
  if (source_) {
    source_.reset();
    emit closed();
  }
}

void PoseWorker::poll() {
  if (!source_) return;
  try {
    const drivers::Pose p = source_->read();
    if (std::isfinite(p.turntable_deg)) last_deg_ = p.turntable_deg;
    emit pose(p.turntable_deg, p.position.x(), p.position.y(), p.position.z(), p.moving, p.in_position);
  } catch (const std::exception& e) {
    poll_->stop();
    source_.reset();
    emit failed(QString::fromStdString(e.what()));
    reconnect_->start();
  }
}

void PoseWorker::command(const char* what, const std::function<void(drivers::PoseSource&)>& f) {
  if (!source_) return;
  try {
    f(*source_);
  } catch (const std::exception& e) {
    emit logLine(QString("%1: %2").arg(what, e.what()));
  }
}

void PoseWorker::jog(double delta) {
  command("jog", [&](drivers::PoseSource& s) { s.moveTo(std::fmod(std::fmod(last_deg_ + delta, 360.0) + 360.0, 360.0)); });
}
void PoseWorker::home() {
  command("home", [](drivers::PoseSource& s) { s.home(); });
}
void PoseWorker::moveTo(double deg) {
  command("move", [&](drivers::PoseSource& s) { s.moveTo(deg); });
}
void PoseWorker::stopMotion() {
  command("stop", [](drivers::PoseSource& s) { s.stop(); });
}

}  // namespace keyturn::studio
