#pragma once
// What the studio shows live: each camera frame goes to the recognition pool
// and to the image panels, each result to the recognition pane and the 3D
// view. Owns the newest frame and result, the rates and latency the status
// line reports, the model recognition runs, the fused belief over the views
// of one turn of the table, and the redraw clock that keeps the window from
// repainting per frame.
#include <QObject>
#include <QString>
#include <cmath>
#include <cstdint>
#include <deque>
#include <memory>
#include <utility>

#include "frame_types.h"
#include "keyturn/learning/live_fusion.h"
#include "keyturn/studio/studio_window.h"
#include "rate_meter.h"

class QLabel;

namespace keyturn::studio {

class CloudView;
class ImagePanel;
class RecognitionPanel;
class RecognitionPool;

// The widgets the live view draws into; the window lays them out and owns them.
struct LiveWidgets {
  ImagePanel* distance = nullptr;
  ImagePanel* amplitude = nullptr;
  ImagePanel* confidence = nullptr;
  CloudView* cloud = nullptr;
  RecognitionPanel* recognition = nullptr;
  QLabel* status = nullptr;
};

class LiveView : public QObject {
  Q_OBJECT
 public:
  // Starts `recognition_threads` recognition threads (describing only, until a model is loaded).
  LiveView(const LiveWidgets& widgets, int recognition_threads, QObject* parent = nullptr);
  ~LiveView() override;  // joins the recognition threads

  void showFrame(const FramePtr& frame);
  void cameraRestarted();        // a reopened camera counts its frames from 0 again
  void setPaused(bool paused);   // frozen: frames and results are ignored
  void setGeodesicPaths(bool on);
  void loadModel(const QString& path);  // "" = describe only; a bad file is shown in the pane
  // The turntable's readout: each frame is fused at the angle last read when it arrived. A turn
  // that starts after the table has rested kRestMs starts a new sequence; at rest no view is
  // added (its bin is taken), so a finished turn's belief stays shown until the next turn.
  void setPose(double turntable_deg, bool moving);
  void poseLost();
  void resetFusion();  // a new object on the table, or another camera: start the sequence again
  const learning::LiveFusion& fusion() const { return fusion_; }
  static constexpr qint64 kRestMs = 3000;
  FramePtr lastFrame() const { return last_frame_; }
  StudioRates rates() const;

 signals:
  void message(const QString& text, int timeout_ms);

 private:
  void showResult(const ViewResultPtr& r);
  void refresh();
  void updateStatus();
  void fuse(const ViewResult& r);

  LiveWidgets widgets_;
  std::unique_ptr<RecognitionPool> pool_;
  bool paused_ = false;
  FramePtr last_frame_;
  ViewResultPtr last_result_;
  std::uint64_t last_result_sequence_ = 0;
  bool frame_fresh_ = false, result_fresh_ = false;
  qint64 last_cloud_ms_ = 0;
  static constexpr int kCloudRedrawHz = 5;
  RateMeter frame_rate_, result_rate_;
  double latency_ms_ = 0, describe_ms_ = 0;
  long frames_ = 0, results_ = 0;
  learning::LiveFusion fusion_;
  bool fusion_fresh_ = true;
  double pose_deg_ = std::nan("");
  bool moving_ = false;
  qint64 rest_since_ms_ = 0;  // when the table last came to rest (0: it has not turned yet)
  std::deque<std::pair<std::uint64_t, double>> frame_poses_;  // frame sequence → the angle when it arrived
};

}  // namespace keyturn::studio
