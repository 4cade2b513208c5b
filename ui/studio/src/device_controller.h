#pragma once
// The studio's devices: the camera and the pose source each on their own
// worker thread, driven by the Devices panel. Owns what they are doing wrong
// (shown in the red banner over the live view, with "Reconnect now") and the
// pose source a capture sequence turns the object with.
#include <QObject>
#include <QString>
#include <QThread>
#include <memory>

#include "camera_worker.h"
#include "frame_types.h"
#include "keyturn/studio/rig_factory.h"

class QLabel;
class QWidget;

namespace keyturn::studio {

class DevicesPanel;
class PoseWorker;

class DeviceController : public QObject {
  Q_OBJECT
 public:
  // Starts the two worker threads and connects the panel's buttons to them.
  DeviceController(RigFactory& factory, DevicesPanel* panel, QObject* parent = nullptr);
  // Ends a running capture after its current view and joins both threads.
  ~DeviceController() override;

  // The problem banner (hidden while both devices answer), for the window's layout to adopt.
  QWidget* banner() const { return banner_; }
  QString bannerText() const;  // "" when the banner is hidden
  // The open pose source; null when none is connected (a capture needs one).
  std::shared_ptr<drivers::PoseSource> poseSource() const { return pose_source_; }

  // A capture sequence on the camera's thread, turning the connected pose source.
  void capture(const CaptureRequest& request);
  void stopCapture();  // after the view being taken

 signals:
  void frameReady(keyturn::studio::FramePtr frame);
  void cameraRestarted();  // opened or reconnected: its frame numbers start again from 0
  // The pose source's readout (10 Hz): the turntable's angle and whether it is turning.
  void poseChanged(double turntable_deg, bool moving);
  void poseLost();  // disconnected: the angles that follow are another table's
  void message(const QString& text, int timeout_ms);
  void captureProgress(int done, int skipped, int total, double angle, keyturn::studio::FramePtr frame,
                       const QString& view);
  void captureFinished(int written, int skipped, bool stopped, const QString& error);

 private:
  void buildBanner();
  void connectPanel();
  void connectCamera();
  void connectPose();
  void setCameraProblem(const QString& problem);
  void setPoseProblem(const QString& problem);
  void updateBanner();
  template <typename F>
  void onCamera(F f) { QMetaObject::invokeMethod(camera_, f, Qt::QueuedConnection); }
  template <typename F>
  void onPose(F f) { QMetaObject::invokeMethod(pose_, f, Qt::QueuedConnection); }

  RigFactory& factory_;
  DevicesPanel* panel_;
  QThread camera_thread_, pose_thread_;
  CameraWorker* camera_ = nullptr;  // lives in camera_thread_, deleted when it finishes
  PoseWorker* pose_ = nullptr;      // lives in pose_thread_, deleted when it finishes
  std::shared_ptr<drivers::PoseSource> pose_source_;
  QString camera_problem_, pose_problem_;
  QWidget* banner_ = nullptr;  // owned by the layout that adopts it
  QLabel* banner_text_ = nullptr;
};

}  // namespace keyturn::studio
