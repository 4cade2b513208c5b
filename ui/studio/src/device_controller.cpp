#include "device_controller.h"

#include <QHBoxLayout>
#include <QLabel>
#include <QPushButton>
#include <optional>

#include "devices_panel.h"
#include "pose_worker.h"

namespace keyturn::studio {

DeviceController::DeviceController(RigFactory& factory, DevicesPanel* panel, QObject* parent)
    : QObject(parent), factory_(factory), panel_(panel) {
  registerStudioMetaTypes();
  camera_ = new CameraWorker(factory_);
  camera_->moveToThread(&camera_thread_);
  QObject::connect(&camera_thread_, &QThread::finished, camera_, &QObject::deleteLater);
  pose_ = new PoseWorker(factory_);
  pose_->moveToThread(&pose_thread_);
  QObject::connect(&pose_thread_, &QThread::finished, pose_, &QObject::deleteLater);
  camera_thread_.setObjectName("camera");
  pose_thread_.setObjectName("pose");
  camera_thread_.start();
  pose_thread_.start();
  buildBanner();
  connectPanel();
  connectCamera();
  connectPose();
}

DeviceController::~DeviceController() {
  camera_->captureStop() = true;  // a running capture ends after its current view
  camera_thread_.quit();
  pose_thread_.quit();
  camera_thread_.wait();
  pose_thread_.wait();
}

void DeviceController::buildBanner() {
  banner_ = new QWidget;
  banner_->setObjectName("banner");
  banner_->setStyleSheet("#banner { background: #c0392b; border-radius: 4px; } #banner QLabel { color: white; }");
  auto* bl = new QHBoxLayout(banner_);
  banner_text_ = new QLabel;
  banner_text_->setObjectName("bannerText");
  banner_text_->setWordWrap(true);
  auto* reconnect = new QPushButton(tr("Reconnect now"));
  bl->addWidget(banner_text_, 1);
  bl->addWidget(reconnect);
  banner_->hide();
  QObject::connect(reconnect, &QPushButton::clicked, this, [this] { onCamera([c = camera_] { c->reconnectNow(); }); });
}

QString DeviceController::bannerText() const { return banner_->isHidden() ? QString() : banner_text_->text(); }

void DeviceController::capture(const CaptureRequest& request) {
  camera_->captureStop() = false;
  onCamera([c = camera_, request, p = pose_source_] { c->capture(request, p); });
}

void DeviceController::stopCapture() { camera_->captureStop() = true; }

// Devices panel → workers.
void DeviceController::connectPanel() {
  QObject::connect(panel_, &DevicesPanel::connectCamera, this, [this] {
    rig::CameraSpec r;
    try {
      r = panel_->cameraSpec();
    } catch (const std::exception& e) {  // a bad address typed, an unwritable configuration
      panel_->cameraFailing(e.what());
      setCameraProblem(tr("Could not open the camera: %1").arg(e.what()));
      return;
    }
    const drivers::TofSettings s = panel_->cameraSettings();
    onCamera([c = camera_, r, s] { c->open(r, s); });
  });
  QObject::connect(panel_, &DevicesPanel::disconnectCamera, this, [this] {
    setCameraProblem(QString());
    onCamera([c = camera_] { c->close(); });
  });
  QObject::connect(panel_, &DevicesPanel::settingsChanged, this, [this] {
    const drivers::TofSettings s = panel_->cameraSettings();
    onCamera([c = camera_, s] { c->configure(s); });
  });
  QObject::connect(panel_, &DevicesPanel::simulatedUnplug, this,
                   [this](bool on) { factory_.setSimulatedCameraUnplugged(on); });
  QObject::connect(panel_, &DevicesPanel::connectPose, this, [this] {
    std::optional<rig::PoseSpec> r;
    try {
      r = panel_->poseSpec();
    } catch (const std::exception& e) {  // a bad endpoint typed
      panel_->poseFailing(e.what());
      setPoseProblem(tr("Could not open the pose source: %1").arg(e.what()));
      return;
    }
    onPose([p = pose_, r] { p->open(r); });
  });
  QObject::connect(panel_, &DevicesPanel::disconnectPose, this, [this] {
    setPoseProblem(QString());
    onPose([p = pose_] { p->close(); });
  });
  QObject::connect(panel_, &DevicesPanel::jog, this, [this](double d) { onPose([p = pose_, d] { p->jog(d); }); });
  QObject::connect(panel_, &DevicesPanel::home, this, [this] { onPose([p = pose_] { p->home(); }); });
  QObject::connect(panel_, &DevicesPanel::moveTo, this, [this](double a) { onPose([p = pose_, a] { p->moveTo(a); }); });
  QObject::connect(panel_, &DevicesPanel::stopMotion, this, [this] { onPose([p = pose_] { p->stopMotion(); }); });
}

// Camera worker → panel, banner and listeners.
void DeviceController::connectCamera() {
  QObject::connect(camera_, &CameraWorker::opened, this, [this](const QString& device, const QString& s) {
    setCameraProblem(QString());
    emit cameraRestarted();
    panel_->cameraConnected(device, s);
    emit message(tr("camera connected: %1").arg(device), 4000);
  });
  QObject::connect(camera_, &CameraWorker::closed, panel_, &DevicesPanel::cameraDisconnected);
  QObject::connect(camera_, &CameraWorker::frameReady, this, &DeviceController::frameReady);
  QObject::connect(camera_, &CameraWorker::rate, panel_, &DevicesPanel::cameraRate);
  QObject::connect(camera_, &CameraWorker::failed, this, [this](const QString& why) {
    panel_->cameraFailing(why);
    setCameraProblem(tr("Camera stopped answering: %1. Reconnecting every second…").arg(why));
  });
  QObject::connect(camera_, &CameraWorker::ended, this, [this](const QString& why) {
    panel_->cameraEnded(why);
    emit message(why, 8000);
  });
  QObject::connect(camera_, &CameraWorker::openFailed, this, [this](const QString& why) {
    panel_->cameraFailing(why);
    setCameraProblem(tr("Could not open the camera: %1").arg(why));
  });
  QObject::connect(camera_, &CameraWorker::recovered, this, [this](const QString& device) {
    setCameraProblem(QString());
    emit cameraRestarted();
    panel_->cameraConnected(device, tr("reconnected"));
    emit message(tr("camera back: %1").arg(device), 6000);
  });
  QObject::connect(camera_, &CameraWorker::logLine, this, [this](const QString& l) { emit message(l, 4000); });
  QObject::connect(camera_, &CameraWorker::captureProgress, this, &DeviceController::captureProgress);
  QObject::connect(camera_, &CameraWorker::captureFinished, this, &DeviceController::captureFinished);
}

// Pose worker → panel, banner and the capture's pose source.
void DeviceController::connectPose() {
  QObject::connect(pose_, &PoseWorker::opened, this,
                   [this](const QString& device, bool can_move, std::shared_ptr<drivers::PoseSource> src) {
                     pose_source_ = std::move(src);
                     setPoseProblem(QString());
                     panel_->poseConnected(device, can_move);
                   });
  QObject::connect(pose_, &PoseWorker::closed, this, [this] {
    pose_source_.reset();
    panel_->poseDisconnected();
    emit poseLost();
  });
  QObject::connect(pose_, &PoseWorker::pose, panel_, &DevicesPanel::showPose);
  QObject::connect(pose_, &PoseWorker::pose, this,
                   [this](double deg, double, double, double, bool moving, bool) { emit poseChanged(deg, moving); });
  QObject::connect(pose_, &PoseWorker::failed, this, [this](const QString& why) {
    panel_->poseFailing(why);
    setPoseProblem(tr("Pose source stopped answering: %1. Reconnecting every second…").arg(why));
  });
  QObject::connect(pose_, &PoseWorker::openFailed, this, [this](const QString& why) {
    panel_->poseFailing(why);
    setPoseProblem(tr("Could not open the pose source: %1").arg(why));
  });
  QObject::connect(pose_, &PoseWorker::recovered, this, [this] { setPoseProblem(QString()); });
  QObject::connect(pose_, &PoseWorker::logLine, this, [this](const QString& l) { emit message(l, 4000); });
}

void DeviceController::setCameraProblem(const QString& problem) {
  camera_problem_ = problem;
  updateBanner();
}

void DeviceController::setPoseProblem(const QString& problem) {
  pose_problem_ = problem;
  updateBanner();
}

void DeviceController::updateBanner() {
  QStringList lines;
  if (!camera_problem_.isEmpty()) lines << camera_problem_;
  if (!pose_problem_.isEmpty()) lines << pose_problem_;
  banner_text_->setText(lines.join("\n"));
  banner_->setVisible(!lines.isEmpty());
}

}  // namespace keyturn::studio
