// The window: lays out the panels, docks and toolbar, and connects the controllers (devices, live
// view, capture, and reconstruct and enroll on one background job) to them and to each other.
#include "keyturn/studio/studio_window.h"

#include <QCloseEvent>
#include <QDockWidget>
#include <QGuiApplication>
#include <QHBoxLayout>
#include <QLabel>
#include <QScreen>
#include <QScrollArea>
#include <QScrollBar>
#include <QSettings>
#include <QSplitter>
#include <QStatusBar>
#include <QTimer>
#include <QToolBar>
#include <QVBoxLayout>

#include "background_job.h"
#include "capture_controller.h"
#include "capture_panel.h"
#include "cloud_view.h"
#include "device_controller.h"
#include "devices_panel.h"
#include "enroll_controller.h"
#include "image_panel.h"
#include "job_status.h"
#include "live_view.h"
#include "reconstruct_controller.h"
#include "recognition_panel.h"

namespace keyturn::studio {

namespace {

// A side panel that scrolls when the window is short instead of setting the window's minimum
// height: the Devices panel (~680 px) over the capture dock made the window 1,025 px tall, more
// than a 1000 px screen. (Its contents keep their width: no labels that grow later.)
QScrollArea* scrolling(QWidget* panel, int max_width) {
  auto* area = new QScrollArea;
  area->setWidget(panel);
  area->setWidgetResizable(true);
  area->setFrameShape(QFrame::NoFrame);
  area->setHorizontalScrollBarPolicy(Qt::ScrollBarAlwaysOff);
  const int bar = area->verticalScrollBar()->sizeHint().width();
  panel->setMaximumWidth(max_width);
  area->setMinimumWidth(panel->minimumSizeHint().width() + bar);
  area->setMaximumWidth(max_width + bar);
  return area;
}

QDockWidget* dock(const QString& title, const char* name, QWidget* contents) {
  auto* d = new QDockWidget(title);
  d->setObjectName(name);
  d->setWidget(contents);
  return d;
}

}  // namespace

StudioWindow::StudioWindow(RigFactory& factory, StudioOptions options, QWidget* parent)
    : QMainWindow(parent), options_(std::move(options)) {
  settings_ = options_.settings_file.empty()
                  ? std::make_unique<QSettings>("keyturn", "studio")
                  : std::make_unique<QSettings>(QString::fromStdString(options_.settings_file), QSettings::IniFormat);
  buildLayout(factory, options_.recognition_threads);
  QSettings& s = *settings_;
  devices_panel_->restore(s);
  capture_panel_->restore(s);
  placeWindow();
  if (!options_.dataset.empty()) capture_panel_->setDataset(QString::fromStdString(options_.dataset));
  const QString model = options_.model.empty() ? s.value("recognition/model").toString()
                                               : QString::fromStdString(options_.model);
  if (!model.isEmpty()) live_->loadModel(model);
  connectDevices(factory);
  if (options_.start_capture) startCaptureWhenReady();
}

StudioWindow::~StudioWindow() = default;

void StudioWindow::buildLayout(RigFactory& factory, int recognition_threads) {
  setWindowTitle("keyturn studio");
  auto* central = new QWidget;
  auto* layout = new QVBoxLayout(central);
  layout->setContentsMargins(4, 4, 4, 4);

  devices_panel_ = new DevicesPanel(factory);
  devices_ = std::make_unique<DeviceController>(factory, devices_panel_);
  layout->addWidget(devices_->banner());

  auto* images = new QHBoxLayout;
  auto* distance = new ImagePanel(tr("Distance"), true);
  auto* amplitude = new ImagePanel(tr("Amplitude"), false);
  auto* confidence = new ImagePanel(tr("Confidence"), false);
  images->addWidget(distance);
  images->addWidget(amplitude);
  images->addWidget(confidence);
  auto* image_row = new QWidget;
  image_row->setLayout(images);
  auto* cloud = new CloudView;
  cloud_ = cloud;
  auto* split = new QSplitter(Qt::Vertical);
  split->addWidget(image_row);
  split->addWidget(cloud);
  split->setChildrenCollapsible(false);
  split->setStretchFactor(0, 2);
  split->setStretchFactor(1, 3);
  split->setSizes({260, 420});
  layout->addWidget(split, 1);
  setCentralWidget(central);

  // The Devices panel takes the window's whole height (the capture dock sits beside it, under the
  // live view): above the capture dock, 1600 × 1000 hid the turntable's jog, Home, Move-to and Stop.
  setCorner(Qt::BottomLeftCorner, Qt::LeftDockWidgetArea);
  setCorner(Qt::TopLeftCorner, Qt::LeftDockWidgetArea);
  addDockWidget(Qt::LeftDockWidgetArea, dock(tr("Devices"), "devicesDock", scrolling(devices_panel_, 420)));
  recognition_panel_ = new RecognitionPanel;
  recognition_panel_->setMaximumWidth(420);
  addDockWidget(Qt::RightDockWidgetArea, dock(tr("Recognition"), "recognitionDock", recognition_panel_));
  capture_panel_ = new CapturePanel;
  capture_dock_ = dock(tr("Capture"), "captureDock", capture_panel_);
  addDockWidget(Qt::BottomDockWidgetArea, capture_dock_);

  auto* status = new QLabel;
  status->setObjectName("rates");
  statusBar()->addPermanentWidget(status, 1);

  live_ = std::make_unique<LiveView>(LiveWidgets{distance, amplitude, confidence, cloud, recognition_panel_, status},
                                     recognition_threads);
  capture_ = std::make_unique<CaptureController>(factory, capture_panel_, *devices_, this);
  connect(devices_.get(), &DeviceController::frameReady, live_.get(), &LiveView::showFrame);
  connect(devices_.get(), &DeviceController::cameraRestarted, live_.get(), &LiveView::cameraRestarted);
  connect(devices_panel_, &DevicesPanel::simObjectChanged, capture_.get(), &CaptureController::labelAsSimObject);
  // The fused belief follows the turntable: each frame at its angle, a new object starts it again.
  connect(devices_.get(), &DeviceController::poseChanged, live_.get(), &LiveView::setPose);
  connect(devices_.get(), &DeviceController::poseLost, live_.get(), &LiveView::poseLost);
  connect(devices_panel_, &DevicesPanel::simObjectChanged, live_.get(), [this] { live_->resetFusion(); });
  connect(devices_.get(), &DeviceController::message, statusBar(), &QStatusBar::showMessage);
  connect(live_.get(), &LiveView::message, statusBar(), &QStatusBar::showMessage);
  connect(capture_.get(), &CaptureController::message, statusBar(), &QStatusBar::showMessage);
  buildToolbar(cloud);
  buildModelActions(cloud);
}

// Reconstruct and Enroll… after a capture: one job at a time, its progress and its outcome (or its
// error, one line) in the status bar; the mesh in the 3D view; recognition on the enrolled model.
void StudioWindow::buildModelActions(CloudView* cloud) {
  job_ = std::make_unique<BackgroundJob>();
  auto* job_status = new JobStatus;
  statusBar()->addPermanentWidget(job_status);
  reconstruct_ = std::make_unique<ReconstructController>(capture_panel_, cloud, *job_);
  reconstruct_->setPoissonDepth(settings_->value("reconstruct/poisson_depth", 0).toInt());
  enroll_ = std::make_unique<EnrollController>(
      *job_, this, [this] { return reconstruct_->folder(); }, [this] { return recognition_panel_->modelPath(); },
      [this] {
        const auto o = capture_panel_->options();
        return std::make_pair(QString::fromStdString(o.cls), QString::fromStdString(o.instance));
      });
  try {
    EnrollRecipe recipe;
    const QSettings& s = *settings_;
    if (s.contains("enroll/cameras")) recipe.cameras = rig::parseSimulatedCameras(s.value("enroll/cameras").toString().toStdString());
    if (s.contains("enroll/elevations")) {
      recipe.elevations.clear();
      for (const QString& e : s.value("enroll/elevations").toString().split(',')) recipe.elevations.push_back(e.toDouble());
    }
    recipe.step_deg = s.value("enroll/step", recipe.step_deg).toDouble();
    enroll_->setRecipe(recipe);
  } catch (const std::exception& e) {
    job_status->fail(tr("settings: enroll/cameras: %1").arg(e.what()));
  }

  auto* tools = addToolBar(tr("Model"));
  tools->setObjectName("modelToolbar");
  show_model_ = tools->addAction(tr("Show model"));
  show_model_->setObjectName("showModel");
  show_model_->setCheckable(true);
  show_model_->setEnabled(false);
  show_model_->setToolTip(tr("The reconstructed mesh in the 3D view instead of the live cloud (M)"));
  show_model_->setShortcut(Qt::Key_M);
  addAction(show_model_);
  connect(show_model_, &QAction::toggled, cloud, &CloudView::setModelShown);

  connect(capture_panel_, &CapturePanel::reconstruct, reconstruct_.get(), &ReconstructController::reconstruct);
  connect(capture_panel_, &CapturePanel::enroll, enroll_.get(), &EnrollController::enroll);
  connect(job_.get(), &BackgroundJob::progressed, job_status, &JobStatus::progress);
  connect(job_status, &JobStatus::cancelRequested, job_.get(), &BackgroundJob::cancel);
  connect(job_.get(), &BackgroundJob::finished, job_status, [job_status](const QString& name, const QString& error) {
    if (!error.isEmpty()) job_status->fail(name + ": " + error);
  });
  connect(reconstruct_.get(), &ReconstructController::failed, job_status, &JobStatus::fail);
  connect(enroll_.get(), &EnrollController::failed, job_status, &JobStatus::fail);
  connect(reconstruct_.get(), &ReconstructController::reconstructed, this, [this, job_status](const QString&, const QString& summary) {
    job_status->succeeded(summary);
    show_model_->setEnabled(true);
    show_model_->setChecked(true);
  });
  connect(enroll_.get(), &EnrollController::enrolled, this, [this, job_status](const QString& model, const QString& summary) {
    live_->loadModel(model);
    job_status->succeeded(summary);
    show_model_->setChecked(false);  // back to the live cloud the new model recognises
  });
}

void StudioWindow::buildToolbar(CloudView* cloud) {

  auto* tools = addToolBar(tr("Live"));
  tools->setObjectName("liveToolbar");
  auto* pause = tools->addAction(tr("Pause live view"));
  pause->setCheckable(true);
  pause->setShortcut(Qt::Key_Space);
  pause->setToolTip(tr("Freeze the live images, 3D view and recognition (Space)"));
  auto* snap = tools->addAction(tr("Snapshot"));
  snap->setShortcut(QKeySequence(Qt::CTRL | Qt::Key_S));
  snap->setToolTip(tr("Save the current frame as PCD + PNGs (Ctrl+S)"));
  auto* paths = tools->addAction(tr("Geodesic paths"));
  paths->setCheckable(true);
  paths->setShortcut(Qt::Key_G);
  paths->setToolTip(tr("Show the geodesic paths from the view's centre to each keypoint (G)"));
  auto* reset = tools->addAction(tr("Reset 3D view"));
  reset->setShortcut(Qt::Key_R);
  for (QAction* a : {pause, snap, paths, reset}) addAction(a);
  connect(pause, &QAction::toggled, live_.get(), &LiveView::setPaused);
  connect(snap, &QAction::triggered, this, [this] { capture_->snapshot(live_->lastFrame()); });
  connect(paths, &QAction::toggled, live_.get(), &LiveView::setGeodesicPaths);
  connect(reset, &QAction::triggered, cloud, &CloudView::resetCamera);
  if (options_.geodesic_paths) paths->setChecked(true);
}

// The window's size and its docks' layout: a size that fits the screen, then the saved ones.
void StudioWindow::placeWindow() {
  // Fits a 1600 × 1000 screen with a title bar; smaller screens get what they have.
  QSize size(1600, 960);
  if (QScreen* screen = QGuiApplication::primaryScreen()) size = size.boundedTo(screen->availableGeometry().size());
  resize(size);
  // The capture dock at its own height, the live view and the side panels above it take the rest.
  resizeDocks({capture_dock_}, {capture_dock_->minimumSizeHint().height()}, Qt::Vertical);
  restoreGeometry(settings_->value("window/geometry").toByteArray());
  restoreState(settings_->value("window/state").toByteArray());
}

// The simulated rig or a recording, when the options ask for one.
void StudioWindow::connectDevices(RigFactory& factory) {
  if (options_.simulated) {
    QString object = QString::fromStdString(options_.sim_object);
    if (object.isEmpty() && !factory.simObjects().empty()) object = QString::fromStdString(factory.simObjects().front().instance);
    devices_panel_->setCameraChoice(rig::CameraSpec::Kind::Simulated, object);
    devices_panel_->setPoseChoice(DevicesPanel::PoseChoice::Simulated);
    emit devices_panel_->simObjectChanged(devices_panel_->simObject());
    // The turntable first: the simulated camera sees the angle it publishes.
    emit devices_panel_->connectPose();
    emit devices_panel_->connectCamera();
  }
  if (!options_.playback.dataset.empty()) {
    devices_panel_->setPlayback(options_.playback);
    // A capture from the recording is labelled as its first view until the user says otherwise.
    capture_->labelAsPlayback(options_.playback.dataset);
    devices_panel_->setCameraChoice(rig::CameraSpec::Kind::Playback, QString());
    devices_panel_->setPoseChoice(DevicesPanel::PoseChoice::Playback);
    emit devices_panel_->connectCamera();
    emit devices_panel_->connectPose();
  }
  if (options_.camera) {  // a camera named as the CLI names it, without a pose source
    const rig::CameraSpec& c = *options_.camera;
    if (c.kind == rig::CameraSpec::Kind::Playback || c.kind == rig::CameraSpec::Kind::OniFile)
      devices_panel_->setPlayback(c.playback);
    if (c.kind == rig::CameraSpec::Kind::OpenNi2) devices_panel_->setOpenNi2Uri(QString::fromStdString(c.openni2_uri));
    if (c.kind == rig::CameraSpec::Kind::Ethernet) devices_panel_->setAddress(QString::fromStdString(c.address));
    // The simulated OpenNI2 camera's default device looks at the studio's simulated object: the one
    // asked for (--object), else the one used last.
    devices_panel_->setCameraChoice(c.kind, QString::fromStdString(options_.sim_object));
    devices_panel_->setPoseChoice(DevicesPanel::PoseChoice::None);
    emit devices_panel_->connectCamera();
  }
}

// Unattended runs: start the capture as soon as both devices answer.
void StudioWindow::startCaptureWhenReady() {
  auto* wait = new QTimer(this);
  connect(wait, &QTimer::timeout, this, [this, wait] {
    if (!devices_->poseSource() || live_->rates().frames == 0) return;
    wait->deleteLater();
    wait->stop();
    capture_panel_->startFromOutside();
  });
  wait->start(100);
}

void StudioWindow::closeEvent(QCloseEvent* e) {
  QSettings& s = *settings_;
  s.setValue("window/geometry", saveGeometry());
  s.setValue("window/state", saveState());
  devices_panel_->save(s);
  capture_panel_->save(s);
  s.setValue("recognition/model", recognition_panel_->modelPath());
  s.sync();
  QMainWindow::closeEvent(e);
}

StudioRates StudioWindow::rates() const { return live_->rates(); }
QString StudioWindow::bannerText() const { return devices_->bannerText(); }
QString StudioWindow::recognisedClass() const { return recognition_panel_->stableClass(); }
double StudioWindow::recognisedAgreement() const { return recognition_panel_->stableAgreement(); }
QString StudioWindow::fusedClass() const { return recognition_panel_->fusedClass(); }
double StudioWindow::fusedBelief() const { return recognition_panel_->fusedBelief(); }
int StudioWindow::fusedViews() const { return recognition_panel_->fusedViews(); }
ShownModel StudioWindow::shownModel() const {
  return {cloud_->modelShown(), cloud_->modelVertices(), cloud_->modelTriangles(), cloud_->modelBounds()};
}

}  // namespace keyturn::studio
