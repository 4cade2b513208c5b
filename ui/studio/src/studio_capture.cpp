// Starting a capture sequence (after saying what the dataset already holds), and snapshots.
#include "studio_window_impl.h"

#include <QDateTime>
#include <QDir>
#include <QMessageBox>
#include <QStatusBar>

#include "keyturn/dataset/dataset.h"
#include "keyturn/rig/frame_files.h"
#include "keyturn/dataset/sidecars.h"

namespace keyturn::studio {

void StudioWindow::Impl::startCapture() {
  const std::string root = capture->dataset();
  rig::CaptureOptions o = capture->options();
  QString problem;
  if (root.empty()) problem = tr("choose a dataset folder first");
  else if (o.cls.empty() || o.instance.empty()) problem = tr("name the class and the instance");
  else if (!pose_source) problem = tr("connect the turntable first");
  if (!problem.isEmpty()) {
    capture->finished(0, 0, false, problem);
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
  if (existing > 0 && !capture->running()) {
    const auto answer = QMessageBox::question(
        w, tr("Views already captured"),
        tr("%1 already holds %2 views of %3 / %4 at elevation %5. They are kept, and the capture takes only the "
           "missing ones of the %6. Go on?")
            .arg(QString::fromStdString(root))
            .arg(existing)
            .arg(QString::fromStdString(o.cls), QString::fromStdString(o.instance),
                 QString::fromStdString(o.elevation_label))
            .arg(total));
    if (answer != QMessageBox::Yes) {
      capture->finished(0, 0, true, QString());
      return;
    }
  }
  // A measured axis (kept with the dataset, as `keyturn capture --calibration` does) wins over the
  // simulated rig's exact one; a real rig without one writes views without the transform.
  o.camera_from_turntable_zero = factory.cameraFromTurntable();
  if (!capture->calibration().empty()) {
    try {
      o.camera_from_turntable_zero = dataset::adoptAxisCalibration(capture->calibration(), root);
    } catch (const std::exception& e) {
      capture->finished(0, 0, false, QString::fromUtf8(e.what()));
      return;
    }
  }
  CaptureRequest req{root, o};
  camera->captureStop() = false;
  capture->progress(0, 0, static_cast<int>(total), o.start_deg, nullptr, QString());
  onCamera([c = camera, req, p = pose_source] { c->capture(req, p); });
}

void StudioWindow::Impl::snapshot() {
  if (!last_frame) {
    w->statusBar()->showMessage(tr("no frame to save"), 3000);
    return;
  }
  const QString dir = capture->dataset().empty() ? QDir::home().filePath("keyturn-snapshots")
                                                 : QString::fromStdString(capture->dataset()) + "/snapshots";
  QDir().mkpath(dir);
  const QString path = dir + "/" + QDateTime::currentDateTimeUtc().toString("yyyyMMdd-HHmmss-zzz") + ".pcd";
  try {
    rig::writeFrameFiles(path.toStdString(), *last_frame);
    w->statusBar()->showMessage(tr("saved %1 (+ distance, amplitude, confidence PNGs)").arg(path), 6000);
  } catch (const std::exception& e) {
    w->statusBar()->showMessage(tr("snapshot failed: %1").arg(e.what()), 8000);
  }
}

}  // namespace keyturn::studio
