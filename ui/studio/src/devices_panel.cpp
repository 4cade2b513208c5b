// The Devices panel's widgets: the camera's and the pose source's groups, which Device page and
// settings each Source shows, and the lists of the cameras found. What the choices mean as specs is
// devices_panel_specs.cpp, what is kept between runs devices_panel_settings.cpp, what the devices
// report devices_panel_status.cpp.
#include "devices_panel.h"

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QGridLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QSpinBox>
#include <QStackedWidget>
#include <QTimer>
#include <QVBoxLayout>

#include "camera_rows.h"
#include "keyturn/drivers/mesasr_api.h"
#include "status_label.h"

namespace keyturn::studio {
namespace {

// A USB list's row for no camera in particular: the first SwissRanger found.
rig::CameraSpec firstUsbCamera() {
  rig::CameraSpec spec;
  spec.kind = rig::CameraSpec::Kind::Usb;
  return spec;
}

}  // namespace

DevicesPanel::DevicesPanel(RigFactory& factory, QWidget* parent) : QWidget(parent), factory_(factory) {
  auto* layout = new QVBoxLayout(this);
  layout->addWidget(cameraGroup());
  layout->addWidget(poseGroup());
  layout->addStretch(1);
  updateCameraKind();
  updatePoseKind();
}

QWidget* DevicesPanel::cameraGroup() {
  auto* box = new QGroupBox(tr("Camera"));
  auto* form = new QFormLayout(box);
  camera_kind_ = new QComboBox;
  for (const CameraRow& row : kCameraRows) camera_kind_->addItem(tr(row.label));  // camera_rows.h
  camera_kind_->setObjectName("cameraKind");
  form->addRow(tr("Source"), camera_kind_);

  camera_where_ = new QStackedWidget;
  sim_object_ = new QComboBox;
  sim_object_->setObjectName("simObject");
  for (const auto& o : factory_.simObjects())
    sim_object_->addItem(QString::fromStdString(o.cls + " / " + o.instance), QString::fromStdString(o.instance));
  auto* usb = new QWidget;
  auto* usb_row = new QHBoxLayout(usb);
  usb_row->setContentsMargins(0, 0, 0, 0);
  usb_list_ = new QComboBox;
  usb_list_->setObjectName("usbCameras");
  auto* rescan = new QPushButton(tr("Rescan"));
  usb_row->addWidget(usb_list_, 1);
  usb_row->addWidget(rescan);
  address_ = new QLineEdit("192.168.1.42");
  address_->setPlaceholderText("IPv4 address");
  address_->setObjectName("cameraAddress");
  camera_where_->addWidget(sim_object_);
  camera_where_->addWidget(usb);
  camera_where_->addWidget(address_);
  // A dataset replayed: its folder, the rate (0 = as recorded) and whether it starts over at the end.
  auto* playback = new QWidget;
  auto* playback_row = new QHBoxLayout(playback);
  playback_row->setContentsMargins(0, 0, 0, 0);
  playback_dataset_ = new QLineEdit;
  playback_dataset_->setObjectName("playbackDataset");
  playback_dataset_->setPlaceholderText(tr("dataset folder"));
  playback_rate_ = new QDoubleSpinBox;
  playback_rate_->setObjectName("playbackRate");
  playback_rate_->setRange(0, 100);
  playback_rate_->setDecimals(1);
  playback_rate_->setSuffix(tr(" /s"));
  playback_rate_->setSpecialValueText(tr("as recorded"));
  playback_rate_->setToolTip(tr("Frames per second (0: the rate the dataset was recorded at)"));
  playback_loop_ = new QCheckBox(tr("Loop"));
  playback_loop_->setChecked(true);
  playback_row->addWidget(playback_dataset_, 1);
  playback_row->addWidget(playback_rate_);
  playback_row->addWidget(playback_loop_);
  camera_where_->addWidget(playback);
  // OpenNI2's devices by URI; the field stays editable for a URI not (yet) listed, empty = the first found.
  auto* openni2 = new QWidget;
  auto* openni2_row = new QHBoxLayout(openni2);
  openni2_row->setContentsMargins(0, 0, 0, 0);
  openni2_uri_ = new QComboBox;
  openni2_uri_->setEditable(true);
  openni2_uri_->setObjectName("openni2Uri");
  openni2_uri_->setToolTip(tr("OpenNI2 device URI (keyturn devices lists them); empty: the first device found"));
  auto* openni2_rescan = new QPushButton(tr("Rescan"));
  openni2_row->addWidget(openni2_uri_, 1);
  openni2_row->addWidget(openni2_rescan);
  camera_where_->addWidget(openni2);
  connect(openni2_rescan, &QPushButton::clicked, this, &DevicesPanel::refreshOpenNi2);
  form->addRow(tr("Device"), camera_where_);

  auto_exposure_ = new QCheckBox(tr("Auto exposure"));
  auto_exposure_->setChecked(false);
  integration_ = new QSpinBox;
  integration_->setRange(0, 255);
  integration_->setValue(30);
  integration_->setToolTip(tr("SR4000 integration time: 0.3 ms + n × 0.1 ms"));
  auto* exposure_row = new QHBoxLayout;
  exposure_row->addWidget(integration_);
  exposure_row->addWidget(auto_exposure_);
  form->addRow(tr("Integration"), exposure_row);
  modulation_ = new QComboBox;
  for (int f : {MF_30MHz, MF_29MHz, MF_31MHz, MF_15MHz, MF_14_5MHz, MF_15_5MHz})
    modulation_->addItem(QString("%1 MHz (%2 m)").arg(drivers::modulationMHz(f)).arg(drivers::nonAmbiguousRange(f), 0, 'f', 1), f);
  form->addRow(tr("Modulation"), modulation_);
  threshold_ = new QSpinBox;
  threshold_->setRange(0, 65535);
  form->addRow(tr("Amplitude threshold"), threshold_);
  fixed_pattern_ = new QCheckBox(tr("Fixed pattern"));
  median_ = new QCheckBox(tr("Median"));
  denoise_ = new QCheckBox(tr("Denoise (ANF)"));
  conf_map_ = new QCheckBox(tr("Confidence"));
  conf_map_->setToolTip(tr("Acquire the confidence map (AM_CONF_MAP)"));
  for (auto* c : {fixed_pattern_, denoise_, conf_map_}) c->setChecked(true);
  auto* flags = new QGridLayout;
  flags->addWidget(fixed_pattern_, 0, 0);
  flags->addWidget(median_, 0, 1);
  flags->addWidget(denoise_, 1, 0);
  flags->addWidget(conf_map_, 1, 1);
  form->addRow(tr("Acquire"), flags);

  camera_button_ = new QPushButton(tr("Connect"));
  camera_button_->setObjectName("cameraConnect");
  camera_button_->setShortcut(QKeySequence(Qt::Key_F5));
  camera_button_->setToolTip(tr("Connect or disconnect the camera (F5)"));
  unplug_ = new QCheckBox(tr("Pull the simulated cable"));
  unplug_->setObjectName("simUnplug");
  auto* row = new QHBoxLayout;
  row->addWidget(camera_button_);
  row->addWidget(unplug_);
  form->addRow(row);
  camera_status_ = new StatusLabel(tr("disconnected"), 3);  // device, maker, settings
  camera_status_->setObjectName("cameraStatus");
  camera_fps_ = new QLabel("–");
  form->addRow(tr("Status"), camera_status_);
  form->addRow(tr("Frame rate"), camera_fps_);

  connect(camera_kind_, qOverload<int>(&QComboBox::currentIndexChanged), this, [this] { updateCameraKind(); });
  connect(sim_object_, qOverload<int>(&QComboBox::currentIndexChanged), this,
          [this] { emit simObjectChanged(simObject()); });
  connect(rescan, &QPushButton::clicked, this, &DevicesPanel::refreshUsb);
  // Hot-plug: while USB is the chosen source, the list follows cameras plugged in or out.
  auto* hotplug = new QTimer(this);
  connect(hotplug, &QTimer::timeout, this, [this] {
    if (cameraKind() == rig::CameraSpec::Kind::Usb && !camera_on_ && factory_.usbCamerasChanged()) refreshUsb();
  });
  hotplug->start(1000);
  connect(camera_button_, &QPushButton::clicked, this, [this] {
    if (camera_on_) emit disconnectCamera();
    else emit connectCamera();
  });
  connect(unplug_, &QCheckBox::toggled, this, &DevicesPanel::simulatedUnplug);
  for (auto* c : {auto_exposure_, median_, denoise_, fixed_pattern_, conf_map_})
    connect(c, &QCheckBox::toggled, this, &DevicesPanel::settingsChanged);
  connect(auto_exposure_, &QCheckBox::toggled, integration_, &QWidget::setDisabled);
  connect(integration_, qOverload<int>(&QSpinBox::valueChanged), this, &DevicesPanel::settingsChanged);
  connect(threshold_, qOverload<int>(&QSpinBox::valueChanged), this, &DevicesPanel::settingsChanged);
  connect(modulation_, qOverload<int>(&QComboBox::currentIndexChanged), this, &DevicesPanel::settingsChanged);
  return box;
}

QWidget* DevicesPanel::poseGroup() {
  auto* box = new QGroupBox(tr("Turntable / robot"));
  auto* form = new QFormLayout(box);
  pose_kind_ = new QComboBox;
  pose_kind_->addItems({tr("None"), tr("Simulated turntable"), tr("Modbus TCP"), tr("Modbus RTU"), tr("CANopen"),
                        tr("Recording (the camera's)")});
  pose_kind_->setCurrentIndex(1);
  form->addRow(tr("Source"), pose_kind_);
  pose_endpoint_ = new QLineEdit;
  form->addRow(tr("Endpoint"), pose_endpoint_);
  pose_profile_ = new QLineEdit("keyturn-sim");
  pose_profile_->setToolTip(tr("Modbus register profile (keyturn-sim or a JSON file), or the CANopen axes file"));
  form->addRow(tr("Profile"), pose_profile_);
  pose_button_ = new QPushButton(tr("Connect"));
  pose_button_->setObjectName("poseConnect");
  pose_button_->setShortcut(QKeySequence(Qt::SHIFT | Qt::Key_F5));
  pose_button_->setToolTip(tr("Connect or disconnect the pose source (Shift+F5)"));
  form->addRow(pose_button_);
  pose_status_ = new StatusLabel(tr("disconnected"), 1);
  pose_status_->setObjectName("poseStatus");
  form->addRow(tr("Status"), pose_status_);

  angle_ = new QLabel("–");
  angle_->setObjectName("poseAngle");
  QFont big = angle_->font();
  big.setPointSizeF(big.pointSizeF() * 2.0);
  big.setBold(true);
  angle_->setFont(big);
  motion_ = new QLabel;
  auto* readout = new QHBoxLayout;
  readout->addWidget(angle_);
  readout->addWidget(motion_, 1);
  form->addRow(tr("Pose"), readout);

  motion_box_ = new QWidget;
  auto* motion = new QVBoxLayout(motion_box_);
  motion->setContentsMargins(0, 0, 0, 0);
  auto* jogs = new QHBoxLayout;
  for (double d : {-5.0, -1.0, 1.0, 5.0}) {
    auto* b = new QPushButton(QString("%1%2°").arg(d > 0 ? "+" : "").arg(d));
    connect(b, &QPushButton::clicked, this, [this, d] { emit jog(d); });
    if (d == -5.0) b->setShortcut(QKeySequence(Qt::CTRL | Qt::Key_Left));
    if (d == 5.0) b->setShortcut(QKeySequence(Qt::CTRL | Qt::Key_Right));
    jogs->addWidget(b);
  }
  motion->addLayout(jogs);
  auto* moves = new QHBoxLayout;
  auto* home_b = new QPushButton(tr("Home"));
  home_b->setShortcut(QKeySequence(Qt::CTRL | Qt::Key_H));
  target_ = new QDoubleSpinBox;
  target_->setRange(0, 359.9);
  target_->setDecimals(1);
  target_->setSuffix("°");
  target_->setObjectName("poseTarget");
  go_ = new QPushButton(tr("Move to"));
  go_->setObjectName("poseMoveTo");
  auto* stop_b = new QPushButton(tr("Stop"));
  stop_b->setShortcut(QKeySequence(Qt::Key_Escape));
  moves->addWidget(home_b);
  moves->addWidget(target_);
  moves->addWidget(go_);
  moves->addWidget(stop_b);
  motion->addLayout(moves);
  form->addRow(motion_box_);
  motion_box_->setEnabled(false);

  connect(pose_kind_, qOverload<int>(&QComboBox::currentIndexChanged), this, [this] { updatePoseKind(); });
  connect(pose_button_, &QPushButton::clicked, this, [this] {
    if (pose_on_) emit disconnectPose();
    else emit connectPose();
  });
  connect(home_b, &QPushButton::clicked, this, &DevicesPanel::home);
  connect(go_, &QPushButton::clicked, this, [this] { emit moveTo(target_->value()); });
  connect(stop_b, &QPushButton::clicked, this, &DevicesPanel::stopMotion);
  return box;
}

void DevicesPanel::updateCameraKind() {
  const rig::CameraSpec::Kind kind = cameraKind();
  camera_where_->setCurrentIndex(camera_kind_->currentIndex());  // a Device page per Source row
  unplug_->setVisible(kind == rig::CameraSpec::Kind::Simulated);
  // The SR4000's settings mean nothing to an OpenNI2 camera.
  const bool sr4000 = kind != rig::CameraSpec::Kind::OpenNi2;
  for (QWidget* w : std::initializer_list<QWidget*>{integration_, auto_exposure_, modulation_, threshold_, median_,
                                                    denoise_, fixed_pattern_, conf_map_})
    if (w) w->setEnabled(sr4000);
  if (kind == rig::CameraSpec::Kind::Usb && usb_list_->count() == 0) refreshUsb();
  if (kind == rig::CameraSpec::Kind::OpenNi2 && openni2_uri_->count() == 0) refreshOpenNi2();
}

void DevicesPanel::updatePoseKind() {
  const auto k = static_cast<PoseChoice>(pose_kind_->currentIndex());
  const bool external = k != PoseChoice::None && k != PoseChoice::Simulated && k != PoseChoice::Playback;
  pose_endpoint_->setEnabled(external);
  pose_profile_->setEnabled(external);
  pose_endpoint_->setPlaceholderText(k == PoseChoice::ModbusTcp   ? "127.0.0.1:1502"
                                     : k == PoseChoice::ModbusRtu ? "/dev/ttyUSB0"
                                     : k == PoseChoice::Can       ? "can0"
                                                                  : "");
}

void DevicesPanel::refreshUsb() {
  usb_list_->clear();
  try {
    const auto cams = factory_.usbCameras();
    for (const auto& found : cams) addFound(usb_list_, found.label, found.spec);
    if (cams.empty()) addFound(usb_list_, tr("no SwissRanger on USB").toStdString(), firstUsbCamera());
  } catch (const std::exception& e) {
    addFound(usb_list_, std::string("USB: ") + e.what(), firstUsbCamera());
  }
}

void DevicesPanel::refreshOpenNi2() {
  const QString typed = openni2_uri_->currentText();
  openni2_uri_->clear();
  try {
    for (const auto& found : factory_.openni2Cameras()) addFound(openni2_uri_, found.label, found.spec);
  } catch (const std::exception& e) {
    addFound(openni2_uri_, std::string("OpenNI2: ") + e.what(), rig::openNi2CameraSpec(""));
  }
  if (openni2_uri_->count() == 0 && !typed.isEmpty()) openni2_uri_->setEditText(typed);
}

}  // namespace keyturn::studio
