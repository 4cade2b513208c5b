#include "camera_worker.h"

#include <QDateTime>

#include "keyturn/core/error.h"
#include "keyturn/dataset/dataset.h"
#include "keyturn/rig/dataset_playback.h"

namespace keyturn::studio {

CameraWorker::CameraWorker(RigFactory& factory) : factory_(factory) {
  live_ = new QTimer(this);
  live_->setInterval(0);  // the camera paces us: acquire() waits for the next frame
  connect(live_, &QTimer::timeout, this, &CameraWorker::acquireOne);
  reconnect_ = new ReconnectLoop(
      [this] {
        try {
          openCamera();
        } catch (...) {
          camera_.reset();
          throw;
        }
      },
      [this] {
        emit recovered(QString::fromStdString(camera_->deviceString()));
        live_->start();
      },
      this);
  connect(reconnect_, &ReconnectLoop::logLine, this, &CameraWorker::logLine);
}

CameraWorker::~CameraWorker() = default;

void CameraWorker::open(const rig::CameraSpec& spec, const drivers::TofSettings& settings) {
  close();
  spec_ = spec;
  settings_ = settings;
  try {
    openCamera();
  } catch (const std::exception& e) {
    camera_.reset();
    emit openFailed(QString::fromStdString(spec_.describe() + ": " + e.what()));
    return;
  }
  const auto s = camera_->settings();
  const bool depth_camera = spec_.kind == rig::CameraSpec::Kind::OpenNi2 || spec_.kind == rig::CameraSpec::Kind::OniFile;
  emit opened(QString::fromStdString(camera_->deviceString()),
              depth_camera ? QString("OpenNI2 · SR4000 settings unused")
                           : QString("integration %1 · %2 MHz · threshold %3")
                                 .arg(s.auto_exposure.enabled ? QString("auto") : QString::number(s.integration_time))
                                 .arg(drivers::modulationMHz(s.modulation_frequency))
                                 .arg(s.amplitude_threshold));
  second_start_ms_ = QDateTime::currentMSecsSinceEpoch();
  frames_in_second_ = 0;
  live_->start();
}

void CameraWorker::openCamera() {
  camera_ = factory_.openCamera(spec_, [this](const std::string& l) { emit logLine(QString::fromStdString(l)); });
  camera_->configure(settings_);
}

void CameraWorker::close() {
  live_->stop();
  reconnect_->stop();
  if (camera_) {
    camera_.reset();
    emit closed();
  }
}

void CameraWorker::configure(const drivers::TofSettings& settings) {
  settings_ = settings;
  if (!camera_) return;
  try {
    camera_->configure(settings_);
  } catch (const std::exception& e) {
    lost(e.what());
  }
}

void CameraWorker::acquireOne() {
  if (!camera_) return;
  try {
    auto frame = std::make_shared<drivers::TofFrame>(camera_->acquire());
    emit frameReady(frame);
  } catch (const rig::EndOfRecording& e) {
    live_->stop();
    emit ended(QString::fromStdString(e.what()));
    return;
  } catch (const std::exception& e) {
    lost(e.what());
    return;
  }
  ++frames_in_second_;
  const qint64 now = QDateTime::currentMSecsSinceEpoch();
  if (now - second_start_ms_ >= 1000) {
    emit rate(1000.0 * frames_in_second_ / static_cast<double>(now - second_start_ms_));
    frames_in_second_ = 0;
    second_start_ms_ = now;
  }
}

void CameraWorker::lost(const std::string& why) {
  live_->stop();
  camera_.reset();
  emit failed(QString::fromStdString(why));
  reconnect_->start();
}

void CameraWorker::reconnectNow() {
  if (!camera_) reconnect_->tryNow();
}

void CameraWorker::capture(const CaptureRequest& request, std::shared_ptr<drivers::PoseSource> pose) {
  if (!camera_ || !pose) {
    emit captureFinished(0, 0, false, camera_ ? "no pose source connected" : "no camera connected");
    return;
  }
  live_->stop();
  capture_stop_ = false;
  rig::CaptureOptions o = request.options;
  o.stop = &capture_stop_;
  try {
    dataset::Dataset dataset(request.dataset);
    const auto report = rig::runCapture(*camera_, *pose, dataset, o, [&](const rig::CaptureProgress& p) {
      FramePtr frame;
      QString view;
      if (p.frame) {
        frame = std::make_shared<drivers::TofFrame>(*p.frame);
        emit frameReady(frame);  // the live view follows the capture
      }
      if (p.record && !p.record->files.empty()) view = QString::fromStdString(p.record->files.front());
      emit captureProgress(static_cast<int>(p.done), static_cast<int>(p.skipped), static_cast<int>(p.total),
                           p.angle_deg, frame, view);
    });
    emit captureFinished(static_cast<int>(report.written), static_cast<int>(report.skipped), report.stopped, QString());
  } catch (const std::exception& e) {
    emit captureFinished(0, 0, false, QString::fromStdString(e.what()));
  }
  if (camera_) live_->start();
}

}  // namespace keyturn::studio
