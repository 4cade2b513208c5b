#pragma once
// The camera's own thread: opens the camera, acquires at its frame rate, runs
// capture sequences (which need the camera to themselves), and when the camera
// stops answering, reports it and keeps trying to open it again.
#include <QObject>
#include <QTimer>

#include "reconnect_loop.h"
#include <atomic>
#include <memory>

#include "frame_types.h"
#include "keyturn/rig/capture.h"
#include "keyturn/studio/rig_factory.h"

namespace keyturn::studio {

struct CaptureRequest {
  std::string dataset;
  rig::CaptureOptions options;
};

class CameraWorker : public QObject {
  Q_OBJECT
 public:
  explicit CameraWorker(RigFactory& factory);
  ~CameraWorker() override;
  // Set from the GUI thread: the capture stops after the view it is taking.
  std::atomic<bool>& captureStop() { return capture_stop_; }

  // Called in the worker's thread (QMetaObject::invokeMethod).
  void open(const rig::CameraSpec& spec, const drivers::TofSettings& settings);
  void close();
  void configure(const drivers::TofSettings& settings);
  void capture(const CaptureRequest& request, std::shared_ptr<drivers::PoseSource> pose);
  void reconnectNow();

 signals:
  void opened(QString device, QString settings_text);
  void closed();
  void frameReady(keyturn::studio::FramePtr frame);
  void openFailed(QString message);  // could not open it (no retries: the user chose it just now)
  void failed(QString message);      // the camera stopped answering; reconnecting
  void ended(QString message);       // a recording played to its end (no reconnecting)
  void recovered(QString device);
  void logLine(QString line);
  void rate(double frames_per_second);
  void captureProgress(int done, int skipped, int total, double angle, keyturn::studio::FramePtr frame, QString view);
  void captureFinished(int written, int skipped, bool stopped, QString error);

 private:
  void openCamera();  // spec_ with settings_; throws
  void acquireOne();
  void lost(const std::string& why);

  RigFactory& factory_;
  std::unique_ptr<drivers::TofCamera> camera_;
  rig::CameraSpec spec_;
  drivers::TofSettings settings_;
  QTimer* live_ = nullptr;
  ReconnectLoop* reconnect_ = nullptr;
  std::atomic<bool> capture_stop_{false};
  int frames_in_second_ = 0;
  qint64 second_start_ms_ = 0;
};

}  // namespace keyturn::studio
