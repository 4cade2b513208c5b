#include "capture_controller.h"

#include <QDateTime>
#include <QDir>
#include <QMessageBox>

#include "capture_panel.h"
#include "device_controller.h"
#include "keyturn/dataset/dataset.h"
#include "keyturn/rig/frame_files.h"
#include "keyturn/dataset/sidecars.h"

namespace keyturn::studio {

CaptureController::CaptureController(RigFactory& factory, CapturePanel* panel, DeviceController& devices,
                                     QWidget* dialog_parent)
    : factory_(factory), panel_(panel), devices_(devices), dialog_parent_(dialog_parent) {
  QObject::connect(panel_, &CapturePanel::start, this, [this] { start(); });
  QObject::connect(panel_, &CapturePanel::resume, this, [this] { start(); });
  QObject::connect(panel_, &CapturePanel::pause, this, [this] { devices_.stopCapture(); });
  QObject::connect(panel_, &CapturePanel::stop, this, [this] { devices_.stopCapture(); });
  QObject::connect(&devices_, &DeviceController::captureProgress, panel_, &CapturePanel::progress);
  QObject::connect(&devices_, &DeviceController::captureFinished, panel_, &CapturePanel::finished);
}

void CaptureController::labelAsSimObject(const QString& instance) {
  for (const auto& o : factory_.simObjects())
    if (QString::fromStdString(o.instance) == instance)
      panel_->setObject(QString::fromStdString(o.cls), QString::fromStdString(o.instance));
}

void CaptureController::labelAsPlayback(const std::string& dataset) {
  try {
    const auto views = dataset::Dataset::readManifest(dataset);
    if (!views.empty())
      panel_->setObject(QString::fromStdString(views.front().key.cls), QString::fromStdString(views.front().key.instance));
  } catch (const std::exception&) {
    // The camera's open names the problem in the banner.
  }
}

void CaptureController::start() {
  const std::string root = panel_->dataset();
  rig::CaptureOptions o = panel_->options();
  QString problem;
  if (root.empty()) problem = tr("choose a dataset folder first");
  else if (o.cls.empty() || o.instance.empty()) problem = tr("name the class and the instance");
  else if (!devices_.poseSource()) problem = tr("connect the turntable first");
  if (!problem.isEmpty()) {
    panel_->finished(0, 0, false, problem);
    return;
  }
  // Views of this sequence already in the dataset are kept and skipped: say so first.
  std::size_t existing = 0;
  try {
    for (const auto& v : dataset::Dataset::readManifest(root))
      existing += v.key.cls == o.cls && v.key.instance == o.instance && v.key.elevation == o.elevation_label;
  } catch (const std::exception&) {
  }
  const auto total = rig::sequenceAngles(o).size();
  if (existing > 0 && !panel_->running()) {
    const auto answer = QMessageBox::question(
        dialog_parent_, tr("Views already captured"),
        tr("%1 already holds %2 views of %3 / %4 at elevation %5. They are kept, and the capture takes only the "
           "missing ones of the %6. Go on?")
            .arg(QString::fromStdString(root))
            .arg(existing)
            .arg(QString::fromStdString(o.cls), QString::fromStdString(o.instance),
                 QString::fromStdString(o.elevation_label))
            .arg(total));
    if (answer != QMessageBox::Yes) {
      panel_->finished(0, 0, true, QString());
      return;
    }
  }
  // A measured axis (kept with the dataset, as `keyturn capture --calibration` does) wins over the
  // simulated rig's exact one; a real rig without one writes views without the transform.
  o.camera_from_turntable_zero = factory_.cameraFromTurntable();
  if (!panel_->calibration().empty()) {
    try {
      o.camera_from_turntable_zero = dataset::adoptAxisCalibration(panel_->calibration(), root);
    } catch (const std::exception& e) {
      panel_->finished(0, 0, false, QString::fromUtf8(e.what()));
      return;
    }
  }
  panel_->progress(0, 0, static_cast<int>(total), o.start_deg, nullptr, QString());
  devices_.capture(CaptureRequest{root, o});
}

void CaptureController::snapshot(const FramePtr& frame) {
  if (!frame) {
    emit message(tr("no frame to save"), 3000);
    return;
  }
  const QString dir = panel_->dataset().empty() ? QDir::home().filePath("keyturn-snapshots")
                                                : QString::fromStdString(panel_->dataset()) + "/" + dataset::kSnapshotsFolder;
  QDir().mkpath(dir);
  const QString path = dir + "/" + QDateTime::currentDateTimeUtc().toString("yyyyMMdd-HHmmss-zzz") + ".pcd";
  try {
    rig::writeFrameFiles(path.toStdString(), *frame);
    emit message(tr("saved %1 (+ distance, amplitude, confidence PNGs)").arg(path), 6000);
  } catch (const std::exception& e) {
    emit message(tr("snapshot failed: %1").arg(e.what()), 8000);
  }
}

}  // namespace keyturn::studio
