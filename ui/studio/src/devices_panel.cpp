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
#include <QResizeEvent>
#include <QSettings>
#include <QSpinBox>
#include <QStackedWidget>
#include <QTimer>
#include <QVBoxLayout>
#include <algorithm>
#include <cmath>

#include "keyturn/drivers/mesasr_api.h"

namespace keyturn::studio {
namespace {

// A device's status: wrapped, a long path (OpenNI2's drivers folders) breaking after its '/'s rather
// than running past the panel's edge, and as tall as its text at its width, so the panel grows by the
// lines a message takes instead of cutting them off (the scroll area around the panel asks it for one
// size, not for a height at its width: asked, QFormLayout answered for another width and cut the text
// off). A problem's whole message is the tooltip too.
class StatusLabel final : public QLabel {
 public:
  StatusLabel(const QString& text, int min_lines) : QLabel(text), min_lines_(min_lines) { setWordWrap(true); }
  QSize minimumSizeHint() const override { return {QLabel::minimumSizeHint().width(), textHeight()}; }
  QSize sizeHint() const override { return {QLabel::sizeHint().width(), textHeight()}; }
  // The layouts take the hints above, made at the label's width, not a height for a width they guess.
  bool hasHeightForWidth() const override { return false; }

 protected:
  void resizeEvent(QResizeEvent* e) override {
    QLabel::resizeEvent(e);
    if (e->size().width() != e->oldSize().width()) updateGeometry();
  }

 private:
  int textHeight() const { return std::max(min_lines_ * fontMetrics().lineSpacing() + 4, heightForWidth(width())); }
  int min_lines_;
};

// A problem as the status shows it, in red: escaped, a line break allowed after every '/'.
QString problemText(const QString& message) {
  QString html = message.toHtmlEscaped();
  html.replace('/', QStringLiteral("/\u200b"));
  return QString("<span style='color:#c0392b'>%1</span>").arg(html);
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
  // In rig::CameraSpec::Kind's order; an .oni recording is chosen as a recording (playback).
  camera_kind_->addItems({tr("Simulated SR4000"), tr("USB"), tr("Ethernet"), tr("Recording (playback)"),
                          tr("OpenNI2 (Kinect, Xtion, Astra)")});
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
    if (camera_kind_->currentIndex() == 1 && !camera_on_ && factory_.usbCamerasChanged()) refreshUsb();
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
  camera_where_->setCurrentIndex(camera_kind_->currentIndex());
  unplug_->setVisible(camera_kind_->currentIndex() == 0);
  // The SR4000's settings mean nothing to an OpenNI2 camera.
  const bool sr4000 = camera_kind_->currentIndex() != static_cast<int>(rig::CameraSpec::Kind::OpenNi2);
  for (QWidget* w : std::initializer_list<QWidget*>{integration_, auto_exposure_, modulation_, threshold_, median_,
                                                    denoise_, fixed_pattern_, conf_map_})
    if (w) w->setEnabled(sr4000);
  if (camera_kind_->currentIndex() == 1 && usb_list_->count() == 0) refreshUsb();
  if (camera_kind_->currentIndex() == static_cast<int>(rig::CameraSpec::Kind::OpenNi2) && openni2_uri_->count() == 0)
    refreshOpenNi2();
}

void DevicesPanel::refreshOpenNi2() {
  const QString typed = openni2_uri_->currentText();
  openni2_uri_->clear();
  try {
    for (const auto& [uri, text] : factory_.openni2Cameras())
      openni2_uri_->addItem(QString::fromStdString(text), QString::fromStdString(uri));
  } catch (const std::exception& e) {
    openni2_uri_->addItem(QString("OpenNI2: %1").arg(e.what()), QString());
  }
  if (openni2_uri_->count() == 0 && !typed.isEmpty()) openni2_uri_->setEditText(typed);
}

QString DevicesPanel::openni2Uri() const {
  // A listed device carries its URI as data; a typed one is the text itself.
  const int i = openni2_uri_->currentIndex();
  if (i >= 0 && openni2_uri_->itemText(i) == openni2_uri_->currentText()) return openni2_uri_->itemData(i).toString();
  return openni2_uri_->currentText().trimmed();
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
    for (const auto& [serial, text] : cams) usb_list_->addItem(QString::fromStdString(text), serial);
    if (cams.empty()) usb_list_->addItem(tr("no SwissRanger on USB"), 0u);
  } catch (const std::exception& e) {
    usb_list_->addItem(QString("USB: %1").arg(e.what()), 0u);
  }
}

rig::CameraSpec DevicesPanel::cameraSpec() const {
  rig::CameraSpec spec;
  switch (static_cast<rig::CameraSpec::Kind>(camera_kind_->currentIndex())) {
    case rig::CameraSpec::Kind::Simulated: return factory_.simulatedCamera(simObject().toStdString());
    case rig::CameraSpec::Kind::Usb:
      spec.kind = rig::CameraSpec::Kind::Usb;
      spec.usb_serial = usb_list_->currentData().toUInt();
      return spec;
    case rig::CameraSpec::Kind::Ethernet: return rig::CameraSpec::parse("eth:" + address_->text().trimmed().toStdString());
    case rig::CameraSpec::Kind::Playback:
    case rig::CameraSpec::Kind::OniFile:
      spec.playback = playback();
      // A path ending in .oni is OpenNI2's recording, as the CLI's playback:FILE.oni.
      spec.kind = rig::CameraSpec::parse("playback:" + spec.playback.dataset).kind;
      return spec;
    case rig::CameraSpec::Kind::OpenNi2:
      spec.kind = rig::CameraSpec::Kind::OpenNi2;
      spec.openni2_uri = openni2Uri().toStdString();
      return spec;
  }
  return spec;
}

rig::PlaybackSpec DevicesPanel::playback() const {
  rig::PlaybackSpec p;
  p.dataset = playback_dataset_->text().trimmed().toStdString();
  p.rate_fps = playback_rate_->value();
  p.loop = playback_loop_->isChecked();
  return p;
}

void DevicesPanel::setPlayback(const rig::PlaybackSpec& p) {
  playback_dataset_->setText(QString::fromStdString(p.dataset));
  playback_rate_->setValue(p.rate_fps);
  playback_loop_->setChecked(p.loop);
}

drivers::TofSettings DevicesPanel::cameraSettings() const {
  drivers::TofSettings s;
  s.integration_time = static_cast<std::uint8_t>(integration_->value());
  s.auto_exposure.enabled = auto_exposure_->isChecked();
  s.modulation_frequency = modulation_->currentData().toInt();
  s.amplitude_threshold = static_cast<std::uint16_t>(threshold_->value());
  std::uint32_t mode = AM_CONV_GRAY;
  if (fixed_pattern_->isChecked()) mode |= AM_COR_FIX_PTRN;
  if (median_->isChecked()) mode |= AM_MEDIAN;
  if (denoise_->isChecked()) mode |= AM_DENOISE_ANF;
  if (conf_map_->isChecked()) mode |= AM_CONF_MAP;
  s.acquire_mode = mode;
  return s;
}

std::optional<rig::PoseSpec> DevicesPanel::poseSpec() const {
  const std::string endpoint = pose_endpoint_->text().trimmed().toStdString();
  rig::PoseSpec spec;
  switch (static_cast<PoseChoice>(pose_kind_->currentIndex())) {
    case PoseChoice::None: return std::nullopt;
    case PoseChoice::Simulated: return spec;
    case PoseChoice::ModbusTcp: spec = rig::PoseSpec::parse("modbus-tcp:" + endpoint); break;
    case PoseChoice::ModbusRtu: spec = rig::PoseSpec::parse("modbus-rtu:" + endpoint); break;
    case PoseChoice::Can: spec = rig::PoseSpec::parse("can:" + endpoint); break;
    case PoseChoice::Playback:
      spec.kind = rig::PoseSpec::Kind::Playback;
      spec.playback = playback();  // the camera's recording: the same timeline
      return spec;
  }
  if (spec.profile.empty()) spec.profile = pose_profile_->text().trimmed().toStdString();
  return spec;
}

QString DevicesPanel::simObject() const { return sim_object_->currentData().toString(); }

void DevicesPanel::setCameraChoice(rig::CameraSpec::Kind kind, const QString& sim_object) {
  if (kind == rig::CameraSpec::Kind::OniFile) kind = rig::CameraSpec::Kind::Playback;  // the same row
  camera_kind_->setCurrentIndex(static_cast<int>(kind));
  const int i = sim_object_->findData(sim_object);
  if (i >= 0) sim_object_->setCurrentIndex(i);
}

void DevicesPanel::setOpenNi2Uri(const QString& uri) {
  // No URI is the first device found: keep the listed one shown rather than blank the box.
  if (!uri.isEmpty()) openni2_uri_->setEditText(uri);
}

void DevicesPanel::setAddress(const QString& address) { address_->setText(address); }

void DevicesPanel::setPoseChoice(PoseChoice choice) { pose_kind_->setCurrentIndex(static_cast<int>(choice)); }

void DevicesPanel::save(QSettings& s) const {
  s.setValue("camera/kind", camera_kind_->currentIndex());
  s.setValue("camera/sim_object", simObject());
  s.setValue("camera/address", address_->text());
  s.setValue("camera/integration", integration_->value());
  s.setValue("camera/auto_exposure", auto_exposure_->isChecked());
  s.setValue("camera/modulation", modulation_->currentIndex());
  s.setValue("camera/threshold", threshold_->value());
  s.setValue("camera/playback_dataset", playback_dataset_->text());
  s.setValue("camera/playback_rate", playback_rate_->value());
  s.setValue("camera/playback_loop", playback_loop_->isChecked());
  s.setValue("camera/openni2_uri", openni2Uri());
  s.setValue("pose/kind", pose_kind_->currentIndex());
  s.setValue("pose/endpoint", pose_endpoint_->text());
  s.setValue("pose/profile", pose_profile_->text());
}

void DevicesPanel::restore(const QSettings& s) {
  camera_kind_->setCurrentIndex(s.value("camera/kind", 0).toInt());
  const int i = sim_object_->findData(s.value("camera/sim_object").toString());
  if (i >= 0) sim_object_->setCurrentIndex(i);
  address_->setText(s.value("camera/address", address_->text()).toString());
  integration_->setValue(s.value("camera/integration", 30).toInt());
  auto_exposure_->setChecked(s.value("camera/auto_exposure", false).toBool());
  modulation_->setCurrentIndex(s.value("camera/modulation", 0).toInt());
  threshold_->setValue(s.value("camera/threshold", 0).toInt());
  playback_dataset_->setText(s.value("camera/playback_dataset").toString());
  playback_rate_->setValue(s.value("camera/playback_rate", 0.0).toDouble());
  playback_loop_->setChecked(s.value("camera/playback_loop", true).toBool());
  openni2_uri_->setEditText(s.value("camera/openni2_uri").toString());
  pose_kind_->setCurrentIndex(s.value("pose/kind", 1).toInt());
  pose_endpoint_->setText(s.value("pose/endpoint").toString());
  pose_profile_->setText(s.value("pose/profile", "keyturn-sim").toString());
}

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
             camera_kind_->currentIndex() == static_cast<int>(rig::CameraSpec::Kind::OpenNi2) && where > 0) {
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
