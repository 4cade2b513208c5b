#pragma once
// The studio window's state, shared by its parts: layout and public API
// (studio_window.cpp), wiring of panels and worker threads (studio_wiring.cpp),
// live display (studio_live.cpp), capture and snapshot (studio_capture.cpp).
#include <QAction>
#include <QDockWidget>
#include <QLabel>
#include <QSettings>
#include <QThread>
#include <memory>

#include "camera_worker.h"
#include "capture_panel.h"
#include "cloud_view.h"
#include "devices_panel.h"
#include "frame_types.h"
#include "image_panel.h"
#include "keyturn/studio/studio_window.h"
#include "pose_worker.h"
#include "rate_meter.h"
#include "recognition_panel.h"
#include "recognition_pool.h"

namespace keyturn::studio {

// Without a model the 3D view still shows the paper's keypoints and geodesics.
std::shared_ptr<const learning::Recognizer> describeOnly();

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
  QDockWidget* capture_dock = nullptr;
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
  double latency_ms = 0, describe_ms = 0;
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

}  // namespace keyturn::studio
