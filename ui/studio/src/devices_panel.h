#pragma once
// Devices: the camera (simulated, USB, Ethernet, a recording, OpenNI2) with its settings, and the
// pose source (simulated turntable, Modbus TCP/RTU, CANopen) with a live
// readout and jog / home / move-to / stop. One file a job: the widgets (devices_panel.cpp), the
// choices as rig's specs (devices_panel_specs.cpp), settings kept between runs
// (devices_panel_settings.cpp), what the devices report (devices_panel_status.cpp).
#include <QWidget>

#include <optional>
#include <string>

#include "keyturn/studio/rig_factory.h"

class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QLineEdit;
class QPushButton;
class QSpinBox;
class QSettings;
class QStackedWidget;

namespace keyturn::studio {

class DevicesPanel : public QWidget {
  Q_OBJECT
 public:
  // The pose sources in the panel's list, in its order.
  enum class PoseChoice { None, Simulated, ModbusTcp, ModbusRtu, Can, Playback };

  DevicesPanel(RigFactory& factory, QWidget* parent = nullptr);

  // The chosen camera as rig's spec (a simulated one's configuration written by the factory).
  // Throws keyturn::Error naming a bad address or endpoint typed in the panel.
  rig::CameraSpec cameraSpec() const;
  drivers::TofSettings cameraSettings() const;
  std::optional<rig::PoseSpec> poseSpec() const;  // none: "None" chosen
  void setCameraChoice(rig::CameraSpec::Kind kind, const QString& sim_object);
  void setPoseChoice(PoseChoice choice);
  void setPlayback(const rig::PlaybackSpec& playback);
  void setOpenNi2Uri(const QString& uri);  // "" = the first OpenNI2 device found
  QString openni2Uri() const;
  void setAddress(const QString& ipv4);
  rig::PlaybackSpec playback() const;
  QString simObject() const;

  void save(QSettings& s) const;
  void restore(const QSettings& s);

 public slots:
  void cameraConnected(const QString& device, const QString& settings);
  void cameraDisconnected();
  void cameraRate(double fps);
  void cameraFailing(const QString& message);
  void cameraEnded(const QString& message);
  void poseConnected(const QString& device, bool can_move);
  void poseDisconnected();
  void poseFailing(const QString& message);
  void showPose(double deg, double x, double y, double z, bool moving, bool in_position);
  void refreshUsb();
  void refreshOpenNi2();

 signals:
  void connectCamera();
  void disconnectCamera();
  void settingsChanged();
  void connectPose();
  void disconnectPose();
  void jog(double delta_deg);
  void home();
  void moveTo(double deg);
  void stopMotion();
  void simulatedUnplug(bool unplugged);
  void simObjectChanged(const QString& instance);

 private:
  QWidget* cameraGroup();
  QWidget* poseGroup();
  void updateCameraKind();
  void updatePoseKind();
  rig::CameraSpec::Kind cameraKind() const;  // the Source row's (camera_rows.h)
  // A found camera's row in a device list: its label, and its spec as the row's data.
  static void addFound(QComboBox* list, const std::string& label, const rig::CameraSpec& spec);
  // The spec of a device list's current row; `fallback` for an empty list.
  static rig::CameraSpec currentSpec(const QComboBox* list, const rig::CameraSpec& fallback);

  RigFactory& factory_;
  bool camera_on_ = false, pose_on_ = false;
  QComboBox *camera_kind_, *sim_object_, *usb_list_, *openni2_uri_, *modulation_, *pose_kind_;
  QLineEdit *address_, *pose_endpoint_, *pose_profile_, *playback_dataset_;
  QDoubleSpinBox* playback_rate_;
  QCheckBox* playback_loop_;
  QStackedWidget* camera_where_;
  QSpinBox *integration_, *threshold_;
  QCheckBox *auto_exposure_, *median_, *denoise_, *fixed_pattern_, *conf_map_, *unplug_;
  QPushButton *camera_button_, *pose_button_, *go_;
  QLabel *camera_status_, *camera_fps_, *pose_status_, *angle_, *motion_;
  QDoubleSpinBox* target_;
  QWidget* motion_box_;
};

}  // namespace keyturn::studio
