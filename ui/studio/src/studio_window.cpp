#include "keyturn/studio/studio_window.h"

#include <QCloseEvent>
#include <QDockWidget>
#include <QGuiApplication>
#include <QHBoxLayout>
#include <QPushButton>
#include <QScreen>
#include <QScrollArea>
#include <QScrollBar>
#include <QSplitter>
#include <QStatusBar>
#include <QTimer>
#include <QToolBar>
#include <QVBoxLayout>

#include "keyturn/dataset/dataset.h"
#include "studio_window_impl.h"

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

}  // namespace

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
  dock_devices->setWidget(scrolling(devices, 420));
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
  capture_dock = dock_cap;

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
  // Fits a 1600 × 1000 screen with a title bar; smaller screens get what they have.
  QSize size(1600, 960);
  if (QScreen* screen = QGuiApplication::primaryScreen()) size = size.boundedTo(screen->availableGeometry().size());
  resize(size);
  // The capture dock at its own height, the live view and the side panels above it take the rest.
  resizeDocks({d_->capture_dock}, {d_->capture_dock->minimumSizeHint().height()}, Qt::Vertical);
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
  if (!d_->options.playback.dataset.empty()) {
    d_->devices->setPlayback(d_->options.playback);
    // A capture from the recording is labelled as its first view until the user says otherwise.
    try {
      const auto views = dataset::Dataset::readManifest(d_->options.playback.dataset);
      if (!views.empty())
        d_->capture->setObject(QString::fromStdString(views.front().key.cls), QString::fromStdString(views.front().key.instance));
    } catch (const std::exception&) {
      // The camera's open names the problem in the banner.
    }
    d_->devices->setCameraChoice(CameraRequest::Kind::Playback, QString());
    d_->devices->setPoseChoice(PoseRequest::Kind::Playback);
    emit d_->devices->connectCamera();
    emit d_->devices->connectPose();
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
