// What the window shows of frames and results, redrawn on a clock.
#include "studio_window_impl.h"

#include <QDateTime>
#include <QStatusBar>

#include "keyturn/core/features.h"

namespace keyturn::studio {

std::shared_ptr<const learning::Recognizer> describeOnly() {
  DescriptorOptions o;
  o.features = {Feature::KPD2, Feature::KPA3, Feature::GKPD2};
  return std::make_shared<learning::Recognizer>(o);
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

}  // namespace keyturn::studio
