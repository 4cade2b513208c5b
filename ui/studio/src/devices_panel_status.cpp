// What the Devices panel shows of the devices as they connect, run, fail and move.
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QLabel>
#include <QPushButton>
#include <QStackedWidget>
#include <cmath>

#include "devices_panel.h"
#include "status_label.h"

namespace keyturn::studio {

void DevicesPanel::cameraConnected(const QString& device, const QString& settings) {
  camera_on_ = true;
  camera_button_->setText(tr("Disconnect"));
  camera_kind_->setEnabled(false);
  camera_where_->setEnabled(false);
  // libMesaSR's device string is long ("VendorID:0x1ad2, ProductID:…, Product:'SR4000'…"): its product and
  // maker in the panel, the whole string in the tooltip.
  QString shown = device;
  const int product = device.indexOf("Product:'");
  const int maker = device.indexOf("Manufacturer:'");
  if (product >= 0) {
    shown = device.mid(product + 9).section('\'', 0, 0);
    if (maker >= 0) shown += " · " + device.mid(maker + 14).section('\'', 0, 0);
  } else if (const int where = device.lastIndexOf(" (");
             cameraKind() == rig::CameraSpec::Kind::OpenNi2 && where > 0) {
    shown = device.left(where);  // an OpenNI2 device's "MODEL (URI)": the Device box shows its URI
  }
  camera_status_->setToolTip(device);
  camera_status_->setText(QString("<b>%1</b><br>%2").arg(shown.toHtmlEscaped(), settings.toHtmlEscaped()));
}

void DevicesPanel::cameraDisconnected() {
  camera_on_ = false;
  camera_button_->setText(tr("Connect"));
  camera_kind_->setEnabled(true);
  camera_where_->setEnabled(true);
  camera_status_->setText(tr("disconnected"));
  camera_status_->setToolTip(QString());
  camera_fps_->setText("–");
}

void DevicesPanel::cameraRate(double fps) { camera_fps_->setText(QString("%1 frames/s").arg(fps, 0, 'f', 1)); }

void DevicesPanel::cameraFailing(const QString& message) {
  camera_status_->setText(problemText(message));
  camera_status_->setToolTip(message);
  camera_fps_->setText("–");
}

void DevicesPanel::cameraEnded(const QString& message) {
  camera_status_->setText(tr("%1 — Disconnect, Connect to play it again").arg(message.toHtmlEscaped()));
  camera_fps_->setText("–");
}

void DevicesPanel::poseConnected(const QString& device, bool can_move) {
  pose_on_ = true;
  pose_button_->setText(tr("Disconnect"));
  pose_kind_->setEnabled(false);
  pose_status_->setText(device);
  pose_status_->setToolTip(device);
  motion_box_->setEnabled(can_move);
}

void DevicesPanel::poseDisconnected() {
  pose_on_ = false;
  pose_button_->setText(tr("Connect"));
  pose_kind_->setEnabled(true);
  pose_status_->setText(tr("disconnected"));
  pose_status_->setToolTip(QString());
  angle_->setText("–");
  motion_->clear();
  motion_box_->setEnabled(false);
}

void DevicesPanel::poseFailing(const QString& message) {
  pose_status_->setText(problemText(message));
  pose_status_->setToolTip(message);
}

void DevicesPanel::showPose(double deg, double x, double y, double z, bool moving, bool in_position) {
  if (std::isfinite(deg)) angle_->setText(QString("%1°").arg(deg, 0, 'f', 2));
  else angle_->setText(QString("%1, %2, %3 mm").arg(x * 1e3, 0, 'f', 1).arg(y * 1e3, 0, 'f', 1).arg(z * 1e3, 0, 'f', 1));
  motion_->setText(moving ? tr("moving") : in_position ? tr("in position") : tr("settling"));
}

}  // namespace keyturn::studio
