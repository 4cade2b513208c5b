// Panels → worker threads, and worker threads → panels.
#include "studio_window_impl.h"

#include <QStatusBar>
#include <QTimer>

namespace keyturn::studio {

void StudioWindow::Impl::wire() {
  registerStudioMetaTypes();
  camera = new CameraWorker(factory);
  camera->moveToThread(&camera_thread);
  QObject::connect(&camera_thread, &QThread::finished, camera, &QObject::deleteLater);
  pose = new PoseWorker(factory);
  pose->moveToThread(&pose_thread);
  QObject::connect(&pose_thread, &QThread::finished, pose, &QObject::deleteLater);
  camera_thread.setObjectName("camera");
  pose_thread.setObjectName("pose");
  camera_thread.start();
  pose_thread.start();
  pool = new RecognitionPool(options.recognition_threads, w);
  pool->setRecognizer(describeOnly());
  recognition->setModel("", pool->recognizer().get());

  // Devices panel → workers.
  QObject::connect(devices, &DevicesPanel::connectCamera, w, [this] {
    rig::CameraSpec r;
    try {
      r = devices->cameraSpec();
    } catch (const std::exception& e) {  // a bad address typed, an unwritable configuration
      camera_problem = tr("Could not open the camera: %1").arg(e.what());
      devices->cameraFailing(e.what());
      updateBanner();
      return;
    }
    const drivers::TofSettings s = devices->cameraSettings();
    onCamera([c = camera, r, s] { c->open(r, s); });
  });
  QObject::connect(devices, &DevicesPanel::disconnectCamera, w, [this] {
    camera_problem.clear();
    updateBanner();
    onCamera([c = camera] { c->close(); });
  });
  QObject::connect(devices, &DevicesPanel::settingsChanged, w, [this] {
    const drivers::TofSettings s = devices->cameraSettings();
    onCamera([c = camera, s] { c->configure(s); });
  });
  QObject::connect(devices, &DevicesPanel::simulatedUnplug, w, [this](bool on) { factory.setSimulatedCameraUnplugged(on); });
  QObject::connect(devices, &DevicesPanel::simObjectChanged, w, [this](const QString& instance) {
    for (const auto& o : factory.simObjects())
      if (QString::fromStdString(o.instance) == instance)
        capture->setObject(QString::fromStdString(o.cls), QString::fromStdString(o.instance));
  });
  QObject::connect(devices, &DevicesPanel::connectPose, w, [this] {
    std::optional<rig::PoseSpec> r;
    try {
      r = devices->poseSpec();
    } catch (const std::exception& e) {  // a bad endpoint typed
      pose_problem = tr("Could not open the pose source: %1").arg(e.what());
      devices->poseFailing(e.what());
      updateBanner();
      return;
    }
    onPose([p = pose, r] { p->open(r); });
  });
  QObject::connect(devices, &DevicesPanel::disconnectPose, w, [this] {
    pose_problem.clear();
    updateBanner();
    onPose([p = pose] { p->close(); });
  });
  QObject::connect(devices, &DevicesPanel::jog, w, [this](double d) { onPose([p = pose, d] { p->jog(d); }); });
  QObject::connect(devices, &DevicesPanel::home, w, [this] { onPose([p = pose] { p->home(); }); });
  QObject::connect(devices, &DevicesPanel::moveTo, w, [this](double a) { onPose([p = pose, a] { p->moveTo(a); }); });
  QObject::connect(devices, &DevicesPanel::stopMotion, w, [this] { onPose([p = pose] { p->stopMotion(); }); });

  // Camera worker → window.
  QObject::connect(camera, &CameraWorker::opened, w, [this](const QString& device, const QString& s) {
    camera_problem.clear();
    last_result_sequence = 0;
    updateBanner();
    devices->cameraConnected(device, s);
    w->statusBar()->showMessage(tr("camera connected: %1").arg(device), 4000);
  });
  QObject::connect(camera, &CameraWorker::closed, devices, &DevicesPanel::cameraDisconnected);
  QObject::connect(camera, &CameraWorker::frameReady, w, [this](const FramePtr& f) { showFrame(f); });
  QObject::connect(camera, &CameraWorker::rate, devices, &DevicesPanel::cameraRate);
  QObject::connect(camera, &CameraWorker::failed, w, [this](const QString& why) {
    camera_problem = tr("Camera stopped answering: %1. Reconnecting every second…").arg(why);
    devices->cameraFailing(why);
    updateBanner();
  });
  QObject::connect(camera, &CameraWorker::ended, w, [this](const QString& why) {
    devices->cameraEnded(why);
    w->statusBar()->showMessage(why, 8000);
  });
  QObject::connect(camera, &CameraWorker::openFailed, w, [this](const QString& why) {
    camera_problem = tr("Could not open the camera: %1").arg(why);
    devices->cameraFailing(why);
    updateBanner();
  });
  QObject::connect(camera, &CameraWorker::recovered, w, [this](const QString& device) {
    camera_problem.clear();
    last_result_sequence = 0;
    updateBanner();
    devices->cameraConnected(device, tr("reconnected"));
    w->statusBar()->showMessage(tr("camera back: %1").arg(device), 6000);
  });
  QObject::connect(camera, &CameraWorker::logLine, w, [this](const QString& l) { w->statusBar()->showMessage(l, 4000); });
  QObject::connect(camera, &CameraWorker::captureProgress, capture, &CapturePanel::progress);
  QObject::connect(camera, &CameraWorker::captureFinished, w,
                   [this](int written, int skipped, bool stopped, const QString& error) {
                     capture->finished(written, skipped, stopped, error);
                   });

  // Pose worker → window.
  QObject::connect(pose, &PoseWorker::opened, w,
                   [this](const QString& device, bool can_move, std::shared_ptr<drivers::PoseSource> src) {
                     pose_source = std::move(src);
                     pose_problem.clear();
                     updateBanner();
                     devices->poseConnected(device, can_move);
                   });
  QObject::connect(pose, &PoseWorker::closed, w, [this] {
    pose_source.reset();
    devices->poseDisconnected();
  });
  QObject::connect(pose, &PoseWorker::pose, devices, &DevicesPanel::showPose);
  QObject::connect(pose, &PoseWorker::failed, w, [this](const QString& why) {
    pose_problem = tr("Pose source stopped answering: %1. Reconnecting every second…").arg(why);
    devices->poseFailing(why);
    updateBanner();
  });
  QObject::connect(pose, &PoseWorker::openFailed, w, [this](const QString& why) {
    pose_problem = tr("Could not open the pose source: %1").arg(why);
    devices->poseFailing(why);
    updateBanner();
  });
  QObject::connect(pose, &PoseWorker::recovered, w, [this] {
    pose_problem.clear();
    updateBanner();
  });
  QObject::connect(pose, &PoseWorker::logLine, w, [this](const QString& l) { w->statusBar()->showMessage(l, 4000); });

  // Capture panel.
  QObject::connect(capture, &CapturePanel::start, w, [this] { startCapture(); });
  QObject::connect(capture, &CapturePanel::resume, w, [this] { startCapture(); });
  QObject::connect(capture, &CapturePanel::pause, w, [this] { camera->captureStop() = true; });
  QObject::connect(capture, &CapturePanel::stop, w, [this] { camera->captureStop() = true; });

  // Recognition.
  QObject::connect(pool, &RecognitionPool::result, w, [this](const ViewResultPtr& r) { showResult(r); });
  QObject::connect(recognition, &RecognitionPanel::loadModel, w, [this](const QString& p) { loadModel(p); });

  auto* redraw = new QTimer(w);
  QObject::connect(redraw, &QTimer::timeout, w, [this] { refresh(); });
  redraw->start(80);
  auto* tick = new QTimer(w);
  QObject::connect(tick, &QTimer::timeout, w, [this] { updateStatus(); });
  tick->start(1000);
}

}  // namespace keyturn::studio
