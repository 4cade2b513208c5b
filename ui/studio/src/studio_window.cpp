#include "keyturn/studio/studio_window.h"

#include <QAction>
#include <QApplication>
#include <QCloseEvent>
#include <QDateTime>
#include <QDir>
#include <QDockWidget>
#include <QElapsedTimer>
#include <QHBoxLayout>
#include <QLabel>
#include <QMessageBox>
#include <QPushButton>
#include <QSettings>
#include <QSplitter>
#include <QStatusBar>
#include <QThread>
#include <QTimer>
#include <QToolBar>
#include <QVBoxLayout>
#include <deque>

#include "camera_worker.h"
#include "capture_panel.h"
#include "cloud_view.h"
#include "devices_panel.h"
#include "frame_types.h"
#include "image_panel.h"
#include "keyturn/core/features.h"
#include "keyturn/learning/feature_spec.h"
#include "keyturn/rig/dataset.h"
#include "keyturn/rig/frame_files.h"
#include "pose_worker.h"
#include "recognition_panel.h"
#include "recognition_pool.h"

namespace keyturn::studio {

namespace {

// Events per second over the last two seconds.
class RateMeter {
 public:
  void tick() {
    const qint64 now = clock_.isValid() ? clock_.elapsed() : (clock_.start(), 0);
    times_.push_back(now);
    while (!times_.empty() && now - times_.front() > 2000) times_.pop_front();
  }
  double rate() const {
    if (times_.size() < 2) return 0;
    const qint64 span = times_.back() - times_.front();
    return span > 0 ? 1000.0 * static_cast<double>(times_.size() - 1) / static_cast<double>(span) : 0;
  }

 private:
  QElapsedTimer clock_;
  std::deque<qint64> times_;
};

// Without a model the 3D view still shows the paper's keypoints and geodesics.
std::shared_ptr<const learning::Recognizer> describeOnly() {
  return std::make_shared<learning::Recognizer>(learning::FeatureParams(),
                                                std::vector<Feature>{Feature::KPD2, Feature::KPA3, Feature::GKPD2});
}

}  // namespace

struct StudioWindow::Impl {
  StudioWindow* w;
  RigFactory& factory;
  StudioOptions options;
  std::unique_ptr<QSettings> settings;

  QThread camera_thread, pose_thread;
  CameraWorker* camera = nullptr;
  PoseWorker* pose = nullptr;
  RecognitionPool* pool = nullptr;
  std::shared_ptr<drivers::PoseSource> pose_source;

  DevicesPanel* devices = nullptr;
  CapturePanel* capture = nullptr;
  RecognitionPanel* recognition = nullptr;
  ImagePanel *distance = nullptr, *amplitude = nullptr, *confidence = nullptr;
  CloudView* cloud = nullptr;
  QWidget* banner = nullptr;
  QLabel* banner_text = nullptr;
  QLabel* status = nullptr;
  QAction *pause_action = nullptr, *paths_action = nullptr;

  bool paused = false;
  QString camera_problem, pose_problem;
  FramePtr last_frame;
  std::uint64_t last_result_sequence = 0;
  ViewResultPtr last_result;
  qint64 last_cloud_ms = 0;
  static constexpr int kCloudRedrawHz = 5;
  bool frame_fresh = false, result_fresh = false;
  RateMeter frame_rate, result_rate;
  double camera_fps = 0, latency_ms = 0, describe_ms = 0;
  long frames = 0, results = 0;

  Impl(StudioWindow* window, RigFactory& f, StudioOptions o) : w(window), factory(f), options(std::move(o)) {}

  void build();
  void wire();
  void showFrame(const FramePtr& frame);
  void showResult(const ViewResultPtr& r);
  void refresh();
  void updateBanner();
  void updateStatus();
  void loadModel(const QString& path);
  void startCapture();
  void snapshot();
  template <typename F>
  void onCamera(F f) { QMetaObject::invokeMethod(camera, f, Qt::QueuedConnection); }
  template <typename F>
  void onPose(F f) { QMetaObject::invokeMethod(pose, f, Qt::QueuedConnection); }
};

void StudioWindow::Impl::build() {
  w->setWindowTitle("keyturn studio");
  auto* central = new QWidget;
  auto* layout = new QVBoxLayout(central);
  layout->setContentsMargins(4, 4, 4, 4);

  banner = new QWidget;
  banner->setObjectName("banner");
  banner->setStyleSheet("#banner { background: #c0392b; border-radius: 4px; } #banner QLabel { color: white; }");
  auto* bl = new QHBoxLayout(banner);
  banner_text = new QLabel;
  banner_text->setObjectName("bannerText");
  banner_text->setWordWrap(true);
  auto* reconnect = new QPushButton(tr("Reconnect now"));
  bl->addWidget(banner_text, 1);
  bl->addWidget(reconnect);
  banner->hide();
  layout->addWidget(banner);
  QObject::connect(reconnect, &QPushButton::clicked, w, [this] {
    onCamera([c = camera] { c->reconnectNow(); });
  });

  auto* images = new QHBoxLayout;
  distance = new ImagePanel(tr("Distance"), true);
  amplitude = new ImagePanel(tr("Amplitude"), false);
  confidence = new ImagePanel(tr("Confidence"), false);
  images->addWidget(distance);
  images->addWidget(amplitude);
  images->addWidget(confidence);
  auto* image_row = new QWidget;
  image_row->setLayout(images);
  cloud = new CloudView;
  auto* split = new QSplitter(Qt::Vertical);
  split->addWidget(image_row);
  split->addWidget(cloud);
  split->setChildrenCollapsible(false);
  split->setStretchFactor(0, 2);
  split->setStretchFactor(1, 3);
  split->setSizes({260, 420});
  layout->addWidget(split, 1);
  w->setCentralWidget(central);

  devices = new DevicesPanel(factory);
  auto* dock_devices = new QDockWidget(tr("Devices"));
  dock_devices->setObjectName("devicesDock");
  dock_devices->setWidget(devices);
  devices->setMaximumWidth(420);
  w->addDockWidget(Qt::LeftDockWidgetArea, dock_devices);

  recognition = new RecognitionPanel;
  auto* dock_rec = new QDockWidget(tr("Recognition"));
  dock_rec->setObjectName("recognitionDock");
  dock_rec->setWidget(recognition);
  recognition->setMaximumWidth(420);
  w->addDockWidget(Qt::RightDockWidgetArea, dock_rec);

  capture = new CapturePanel;
  auto* dock_cap = new QDockWidget(tr("Capture"));
  dock_cap->setObjectName("captureDock");
  dock_cap->setWidget(capture);
  w->addDockWidget(Qt::BottomDockWidgetArea, dock_cap);

  auto* tools = w->addToolBar(tr("Live"));
  tools->setObjectName("liveToolbar");
  pause_action = tools->addAction(tr("Pause live view"));
  pause_action->setCheckable(true);
  pause_action->setShortcut(Qt::Key_Space);
  pause_action->setToolTip(tr("Freeze the live images, 3D view and recognition (Space)"));
  auto* snap = tools->addAction(tr("Snapshot"));
  snap->setShortcut(QKeySequence(Qt::CTRL | Qt::Key_S));
  snap->setToolTip(tr("Save the current frame as PCD + PNGs (Ctrl+S)"));
  paths_action = tools->addAction(tr("Geodesic paths"));
  paths_action->setCheckable(true);
  paths_action->setShortcut(Qt::Key_G);
  paths_action->setToolTip(tr("Show the geodesic paths from the view's centre to each keypoint (G)"));
  auto* reset = tools->addAction(tr("Reset 3D view"));
  reset->setShortcut(Qt::Key_R);
  for (QAction* a : {pause_action, snap, paths_action, reset}) w->addAction(a);
  QObject::connect(pause_action, &QAction::toggled, w, [this](bool on) { paused = on; });
  QObject::connect(snap, &QAction::triggered, w, [this] { snapshot(); });
  QObject::connect(paths_action, &QAction::toggled, w, [this](bool on) { pool->setGeodesicPaths(on); });
  QObject::connect(reset, &QAction::triggered, w, [this] { cloud->resetCamera(); });

  status = new QLabel;
  status->setObjectName("rates");
  w->statusBar()->addPermanentWidget(status, 1);
}

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
    const CameraRequest r = devices->cameraRequest();
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
    const PoseRequest r = devices->poseRequest();
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
  QObject::connect(camera, &CameraWorker::rate, w, [this](double fps) {
    camera_fps = fps;
    devices->cameraRate(fps);
  });
  QObject::connect(camera, &CameraWorker::failed, w, [this](const QString& why) {
    camera_problem = tr("Camera stopped answering: %1. Reconnecting every second…").arg(why);
    devices->cameraFailing(why);
    camera_fps = 0;
    updateBanner();
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

void StudioWindow::Impl::showFrame(const FramePtr& frame) {
  if (paused || !frame) return;
  last_frame = frame;
  frame_fresh = true;
  ++frames;
  frame_rate.tick();
  pool->submit(frame);
}

void StudioWindow::Impl::showResult(const ViewResultPtr& r) {
  if (paused || !r || !r->frame) return;
  // Two workers can finish out of order: never step back to an older frame.
  // (A reopened camera counts from 0 again: opened / recovered reset the mark.)
  if (r->frame->sequence < last_result_sequence) return;
  last_result_sequence = r->frame->sequence;
  if (r->recognition) {
    ++results;
    result_rate.tick();
    latency_ms = r->latency_ms;
    describe_ms = r->recognition->total_ms;
    last_result = r;
    result_fresh = true;
  }
  recognition->record(r);
}

// Every repaint recomposites the whole window in software OpenGL (the 3D view
// makes it a GL window), so the window is redrawn on this clock, not per frame:
// 12 redraws a second look live and leave the CPU to recognition (docs/benchmarks.md).
void StudioWindow::Impl::refresh() {
  if (frame_fresh && last_frame) {
    frame_fresh = false;
    const FramePtr frame = last_frame;
    const int fw = static_cast<int>(frame->width), fh = static_cast<int>(frame->height);
    ImageScale s;
    const double mpc = drivers::nonAmbiguousRange(frame->settings.modulation_frequency) / 65535.0;
    distance->setImage(distanceImage(frame->distance, fw, fh, mpc, &s), s);
    ImageScale a;
    amplitude->setImage(greyImage(frame->amplitude, fw, fh, &a), a);
    if (!frame->confidence.empty()) {
      ImageScale c;
      confidence->setImage(greyImage(frame->confidence, fw, fh, &c, false), c);
    }
  }
  recognition->refresh();
  // The 3D view is drawn in software here (llvmpipe): at 5 frames/s it costs a
  // fifth of a core instead of half (docs/benchmarks.md).
  const qint64 now = QDateTime::currentMSecsSinceEpoch();
  if (result_fresh && last_result && now - last_cloud_ms >= 1000 / kCloudRedrawHz) {
    last_cloud_ms = now;
    result_fresh = false;
    const auto& rec = *last_result->recognition;
    cloud->show(rec.filtered.points, rec.descriptor.keypoints, last_result->geodesic_paths);
  }
}

void StudioWindow::Impl::updateBanner() {
  QStringList lines;
  if (!camera_problem.isEmpty()) lines << camera_problem;
  if (!pose_problem.isEmpty()) lines << pose_problem;
  banner_text->setText(lines.join("\n"));
  banner->setVisible(!lines.isEmpty());
}

void StudioWindow::Impl::updateStatus() {
  const StudioRates r = w->rates();
  status->setText(QString("camera %1 frames/s · recognition %2 frames/s on %3 threads · latency %4 ms · describe %5 ms · %6 dropped")
                      .arg(r.camera_fps, 0, 'f', 1)
                      .arg(r.recognition_fps, 0, 'f', 1)
                      .arg(pool->threads())
                      .arg(r.latency_ms, 0, 'f', 0)
                      .arg(r.describe_ms, 0, 'f', 0)
                      .arg(r.dropped));
}

void StudioWindow::Impl::loadModel(const QString& path) {
  if (path.trimmed().isEmpty()) {
    pool->setRecognizer(describeOnly());
    recognition->setModel("", pool->recognizer().get());
    return;
  }
  try {
    auto r = std::make_shared<learning::Recognizer>(learning::Recognizer::load(path.toStdString()));
    pool->setRecognizer(r);
    recognition->setModel(path, r.get());
    w->statusBar()->showMessage(tr("model loaded: %1").arg(path), 4000);
  } catch (const std::exception& e) {
    recognition->setModel(path, nullptr, QString::fromUtf8(e.what()));
  }
}

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
    for (const auto& v : rig::Dataset::readManifest(root))
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
  o.camera_from_turntable_zero = factory.cameraFromTurntable();
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

StudioWindow::StudioWindow(RigFactory& factory, StudioOptions options, QWidget* parent)
    : QMainWindow(parent), d_(std::make_unique<Impl>(this, factory, std::move(options))) {
  d_->settings = d_->options.settings_file.empty()
                     ? std::make_unique<QSettings>("keyturn", "studio")
                     : std::make_unique<QSettings>(QString::fromStdString(d_->options.settings_file), QSettings::IniFormat);
  d_->build();
  d_->wire();
  QSettings& s = *d_->settings;
  d_->devices->restore(s);
  d_->capture->restore(s);
  resize(1600, 1000);
  restoreGeometry(s.value("window/geometry").toByteArray());
  restoreState(s.value("window/state").toByteArray());
  if (!d_->options.dataset.empty()) d_->capture->setDataset(QString::fromStdString(d_->options.dataset));
  const QString model = d_->options.model.empty() ? s.value("recognition/model").toString()
                                                  : QString::fromStdString(d_->options.model);
  if (!model.isEmpty()) d_->loadModel(model);
  if (d_->options.simulated) {
    QString object = QString::fromStdString(d_->options.sim_object);
    if (object.isEmpty() && !factory.simObjects().empty()) object = QString::fromStdString(factory.simObjects().front().instance);
    d_->devices->setCameraChoice(CameraRequest::Kind::Simulated, object);
    d_->devices->setPoseChoice(PoseRequest::Kind::Simulated);
    emit d_->devices->simObjectChanged(d_->devices->simObject());
    // The turntable first: the simulated camera sees the angle it publishes.
    emit d_->devices->connectPose();
    emit d_->devices->connectCamera();
  }
  if (d_->options.geodesic_paths) d_->paths_action->setChecked(true);
  if (d_->options.start_capture) {
    // Unattended runs: start as soon as both devices answer.
    auto* wait = new QTimer(this);
    connect(wait, &QTimer::timeout, this, [this, wait] {
      if (!d_->pose_source || d_->frames == 0) return;
      wait->deleteLater();
      wait->stop();
      d_->capture->startFromOutside();
    });
    wait->start(100);
  }
}

StudioWindow::~StudioWindow() {
  d_->camera->captureStop() = true;  // a running capture ends after its current view
  d_->camera_thread.quit();
  d_->pose_thread.quit();
  d_->camera_thread.wait();
  d_->pose_thread.wait();
  delete d_->pool;  // joins the recognition threads while the window's state still exists
  d_->pool = nullptr;
}

void StudioWindow::closeEvent(QCloseEvent* e) {
  QSettings& s = *d_->settings;
  s.setValue("window/geometry", saveGeometry());
  s.setValue("window/state", saveState());
  d_->devices->save(s);
  d_->capture->save(s);
  s.setValue("recognition/model", d_->recognition->modelPath());
  s.sync();
  QMainWindow::closeEvent(e);
}

StudioRates StudioWindow::rates() const {
  StudioRates r;
  r.camera_fps = d_->frame_rate.rate();
  r.recognition_fps = d_->result_rate.rate();
  r.latency_ms = d_->latency_ms;
  r.describe_ms = d_->describe_ms;
  r.frames = d_->frames;
  r.results = d_->results;
  r.dropped = d_->pool->dropped();
  return r;
}

QString StudioWindow::bannerText() const { return d_->banner->isHidden() ? QString() : d_->banner_text->text(); }
QString StudioWindow::recognisedClass() const { return d_->recognition->stableClass(); }
double StudioWindow::recognisedAgreement() const { return d_->recognition->stableAgreement(); }

}  // namespace keyturn::studio
