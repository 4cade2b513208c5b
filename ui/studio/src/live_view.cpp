#include "live_view.h"

#include <QDateTime>
#include <QLabel>
#include <QTimer>

#include "cloud_view.h"
#include "image_panel.h"
#include "keyturn/core/features.h"
#include "recognition_panel.h"
#include "recognition_pool.h"

namespace keyturn::studio {

namespace {

// Without a model the 3D view still shows the paper's keypoints and geodesics.
std::shared_ptr<const learning::Recognizer> describeOnly() {
  DescriptorOptions o;
  o.features = {Feature::KPD2, Feature::KPA3, Feature::GKPD2};
  return std::make_shared<learning::Recognizer>(o);
}

}  // namespace

LiveView::LiveView(const LiveWidgets& widgets, int recognition_threads, QObject* parent)
    : QObject(parent), widgets_(widgets), pool_(std::make_unique<RecognitionPool>(recognition_threads)) {
  registerStudioMetaTypes();
  pool_->setRecognizer(describeOnly());
  widgets_.recognition->setModel("", pool_->recognizer().get());
  QObject::connect(pool_.get(), &RecognitionPool::result, this, [this](const ViewResultPtr& r) { showResult(r); });
  QObject::connect(widgets_.recognition, &RecognitionPanel::loadModel, this, [this](const QString& p) { loadModel(p); });
  auto* redraw = new QTimer(this);
  QObject::connect(redraw, &QTimer::timeout, this, [this] { refresh(); });
  redraw->start(80);
  auto* tick = new QTimer(this);
  QObject::connect(tick, &QTimer::timeout, this, [this] { updateStatus(); });
  tick->start(1000);
}

LiveView::~LiveView() = default;

void LiveView::showFrame(const FramePtr& frame) {
  if (paused_ || !frame) return;
  last_frame_ = frame;
  frame_fresh_ = true;
  frame_poses_.emplace_back(frame->sequence, pose_deg_);
  if (frame_poses_.size() > 256) frame_poses_.pop_front();
  ++frames_;
  frame_rate_.tick();
  pool_->submit(frame);
}

void LiveView::cameraRestarted() {
  pool_->restart();
  last_result_sequence_ = 0;
  frame_poses_.clear();
  resetFusion();
}

void LiveView::setPose(double deg, bool moving) {
  const qint64 now = QDateTime::currentMSecsSinceEpoch();
  if (moving && !moving_ && (rest_since_ms_ == 0 || now - rest_since_ms_ >= kRestMs)) resetFusion();
  if (!moving && moving_) rest_since_ms_ = now;
  pose_deg_ = deg;
  moving_ = moving;
}

void LiveView::poseLost() {
  pose_deg_ = std::nan("");
  moving_ = false;
  rest_since_ms_ = 0;
  resetFusion();
}

void LiveView::resetFusion() {
  fusion_.reset();
  fusion_fresh_ = true;
}

// One more view of the turn, at the angle the table had when its frame arrived.
void LiveView::fuse(const ViewResult& r) {
  if (!r.recognition || !r.recognizer || r.recognizer != pool_->recognizer() || !r.recognizer->hasModel()) return;
  double az = std::nan("");
  for (const auto& [sequence, deg] : frame_poses_)
    if (sequence == r.frame->sequence) az = deg;
  const auto& rec = *r.recognition;
  if (fusion_.add(rec.answer, rec.score, rec.probabilities, rec.features, az)) fusion_fresh_ = true;
}

void LiveView::setPaused(bool paused) { paused_ = paused; }

void LiveView::setGeodesicPaths(bool on) { pool_->setGeodesicPaths(on); }

void LiveView::showResult(const ViewResultPtr& r) {
  if (paused_ || !r || !r->frame) return;
  // A result of the camera before a reconnect: its sequence would lift the mark below above the new
  // camera's frames, and every result of theirs would be dropped until it counted past it.
  if (r->epoch != pool_->epoch()) return;
  // Two workers can finish out of order: never step back to an older frame.
  // (A reopened camera counts from 0 again: cameraRestarted() resets the mark.)
  if (r->frame->sequence < last_result_sequence_) return;
  last_result_sequence_ = r->frame->sequence;
  if (r->recognition) {
    ++results_;
    result_rate_.tick();
    latency_ms_ = r->latency_ms;
    describe_ms_ = r->recognition->total_ms;
    last_result_ = r;
    result_fresh_ = true;
    fuse(*r);
  }
  widgets_.recognition->record(r);
}

// Every repaint recomposites the whole window in software OpenGL (the 3D view
// makes it a GL window), so the window is redrawn on this clock, not per frame:
// 12 redraws a second look live and leave the CPU to recognition (docs/benchmarks.md).
void LiveView::refresh() {
  if (frame_fresh_ && last_frame_) {
    frame_fresh_ = false;
    const FramePtr frame = last_frame_;
    const int fw = static_cast<int>(frame->width), fh = static_cast<int>(frame->height);
    ImageScale s;
    // An SR4000's raw distance spans its non-ambiguous range; a depth camera's depth has its unit.
    const auto& depth = frame->depth_camera;
    const double mpc = depth ? depth->depth_unit_m : drivers::nonAmbiguousRange(frame->settings.modulation_frequency) / 65535.0;
    widgets_.distance->setTitle(depth ? tr("Depth") : tr("Distance"));
    widgets_.distance->setImage(distanceImage(frame->distance, fw, fh, mpc, &s), s);
    ImageScale a;
    if (depth && !depth->colour.empty()) {  // a depth camera's colour where the SR4000 has amplitude
      widgets_.amplitude->setTitle(depth->registered ? tr("Colour (registered)") : tr("Colour"));
      widgets_.amplitude->setImage(rgbImage(depth->colour, static_cast<int>(depth->colour_width),
                                            static_cast<int>(depth->colour_height)), a);
    } else if (!depth || !frame->amplitude.empty()) {
      // (A depth camera's frame that came without its colour, as one does when the colour stream
      // lags under load, leaves the last colour image up rather than flashing an empty "IR".)
      widgets_.amplitude->setTitle(depth ? tr("IR") : tr("Amplitude"));
      widgets_.amplitude->setImage(greyImage(frame->amplitude, fw, fh, &a), a);
    } else if (widgets_.amplitude->image().isNull()) {  // a depth camera with neither, so far
      widgets_.amplitude->setTitle(tr("Colour"));
      widgets_.amplitude->setPlaceholder(tr("none from this camera"));
    }
    if (!frame->confidence.empty()) {
      ImageScale c;
      widgets_.confidence->setImage(greyImage(frame->confidence, fw, fh, &c, false), c);
    } else if (!widgets_.confidence->image().isNull() || depth) {
      // A depth camera has no confidence image: say so rather than "no camera" beside its live images.
      widgets_.confidence->setPlaceholder(tr("none from this camera"));
      widgets_.confidence->setImage(QImage(), ImageScale());
    }
  }
  widgets_.recognition->refresh();
  if (fusion_fresh_) {
    fusion_fresh_ = false;
    widgets_.recognition->showFusion(fusion_);
  }
  // The 3D view is drawn in software here (llvmpipe): at 5 frames/s it costs a
  // fifth of a core instead of half (docs/benchmarks.md).
  const qint64 now = QDateTime::currentMSecsSinceEpoch();
  if (result_fresh_ && last_result_ && now - last_cloud_ms_ >= 1000 / kCloudRedrawHz) {
    last_cloud_ms_ = now;
    result_fresh_ = false;
    const auto& rec = *last_result_->recognition;
    widgets_.cloud->show(rec.filtered.points, rec.descriptor.keypoints, last_result_->geodesic_paths);
  }
}

StudioRates LiveView::rates() const {
  StudioRates r;
  r.camera_fps = frame_rate_.rate();
  r.recognition_fps = result_rate_.rate();
  r.latency_ms = latency_ms_;
  r.describe_ms = describe_ms_;
  r.frames = frames_;
  r.results = results_;
  r.dropped = pool_->dropped();
  return r;
}

void LiveView::updateStatus() {
  const StudioRates r = rates();
  widgets_.status->setText(
      QString("camera %1 frames/s · recognition %2 frames/s on %3 threads · latency %4 ms · describe %5 ms · %6 dropped")
          .arg(r.camera_fps, 0, 'f', 1)
          .arg(r.recognition_fps, 0, 'f', 1)
          .arg(pool_->threads())
          .arg(r.latency_ms, 0, 'f', 0)
          .arg(r.describe_ms, 0, 'f', 0)
          .arg(r.dropped));
}

void LiveView::loadModel(const QString& path) {
  if (path.trimmed().isEmpty()) {
    pool_->setRecognizer(describeOnly());
    widgets_.recognition->setModel("", pool_->recognizer().get());
    fusion_ = learning::LiveFusion();
    resetFusion();
    return;
  }
  try {
    auto r = std::make_shared<learning::Recognizer>(learning::Recognizer::load(path.toStdString()));
    pool_->setRecognizer(r);
    fusion_ = learning::LiveFusion(r->info());
    resetFusion();
    widgets_.recognition->setModel(path, r.get());
    emit message(tr("model loaded: %1").arg(path), 4000);
  } catch (const std::exception& e) {
    widgets_.recognition->setModel(path, nullptr, QString::fromUtf8(e.what()));
  }
}

}  // namespace keyturn::studio
