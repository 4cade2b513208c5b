#pragma once
// The studio's capture: starting a sequence from the Capture panel (after
// checking what it needs and saying what the dataset already holds), the
// object the capture is labelled as, and snapshots of the live frame.
#include <QObject>
#include <QString>
#include <string>

#include "frame_types.h"
#include "keyturn/studio/rig_factory.h"

class QWidget;

namespace keyturn::studio {

class CapturePanel;
class DeviceController;

class CaptureController : public QObject {
  Q_OBJECT
 public:
  // Questions are asked over `dialog_parent`; the sequence runs on `devices`' camera thread.
  CaptureController(RigFactory& factory, CapturePanel* panel, DeviceController& devices, QWidget* dialog_parent);

  // Label the capture as the simulated turntable's object `instance` (unknown ones change nothing).
  void labelAsSimObject(const QString& instance);
  // Label the capture as the recording's first view; an unreadable recording changes nothing.
  void labelAsPlayback(const std::string& dataset);
  // Save `frame` as PCD + PNGs in the dataset's snapshots/ (or ~/keyturn-snapshots).
  void snapshot(const FramePtr& frame);

 signals:
  void message(const QString& text, int timeout_ms);

 private:
  void start();

  RigFactory& factory_;
  CapturePanel* panel_;
  DeviceController& devices_;
  QWidget* dialog_parent_;
};

}  // namespace keyturn::studio
