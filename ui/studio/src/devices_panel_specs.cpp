// The Devices panel's choices as rig's typed specs and the SR4000's settings (libMesaSR's AM_* bits),
// and the specs shown back in its widgets.
#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QLineEdit>
#include <QSpinBox>

#include <iterator>

#include "camera_rows.h"
#include "devices_panel.h"
#include "keyturn/drivers/mesasr_api.h"

namespace keyturn::studio {

rig::CameraSpec::Kind cameraKindOfRow(int row) {
  const bool in_range = row >= 0 && row < static_cast<int>(std::size(kCameraRows));
  return kCameraRows[in_range ? row : 0].kind;
}

int rowOfCameraKind(rig::CameraSpec::Kind kind) {
  if (kind == rig::CameraSpec::Kind::OniFile) kind = rig::CameraSpec::Kind::Playback;  // the same row
  for (std::size_t row = 0; row < std::size(kCameraRows); ++row)
    if (kCameraRows[row].kind == kind) return static_cast<int>(row);
  return 0;
}

rig::CameraSpec::Kind DevicesPanel::cameraKind() const { return cameraKindOfRow(camera_kind_->currentIndex()); }

// The row's data is the spec's text (device_spec.h: toString parses back to the spec).
void DevicesPanel::addFound(QComboBox* list, const std::string& label, const rig::CameraSpec& spec) {
  list->addItem(QString::fromStdString(label), QString::fromStdString(spec.toString()));
}

rig::CameraSpec DevicesPanel::currentSpec(const QComboBox* list, const rig::CameraSpec& fallback) {
  const QString text = list->currentData().toString();
  return text.isEmpty() ? fallback : rig::CameraSpec::parse(text.toStdString());
}

rig::CameraSpec DevicesPanel::cameraSpec() const {
  rig::CameraSpec spec;
  switch (cameraKind()) {
    case rig::CameraSpec::Kind::Simulated: return factory_.simulatedCamera(simObject().toStdString());
    case rig::CameraSpec::Kind::Usb:
      spec.kind = rig::CameraSpec::Kind::Usb;  // none listed: the first SwissRanger found
      return currentSpec(usb_list_, spec);
    case rig::CameraSpec::Kind::Ethernet: return rig::CameraSpec::parse("eth:" + address_->text().trimmed().toStdString());
    case rig::CameraSpec::Kind::Playback:
    case rig::CameraSpec::Kind::OniFile:
      spec.playback = playback();
      // A path ending in .oni is OpenNI2's recording, as the CLI's playback:FILE.oni.
      spec.kind = rig::CameraSpec::parse("playback:" + spec.playback.dataset).kind;
      return spec;
    case rig::CameraSpec::Kind::OpenNi2:
      // The simulated OpenNI2 camera's default device looks at the object chosen for the simulated rig.
      if (openni2Uri() == RigFactory::kSimulatedOpenNi2Default)
        return factory_.simulatedOpenNi2Camera(simObject().toStdString());
      return rig::openNi2CameraSpec(openni2Uri().toStdString());
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

QString DevicesPanel::openni2Uri() const {
  // A listed device carries its spec as data; a typed URI is the text itself.
  const int i = openni2_uri_->currentIndex();
  if (i >= 0 && openni2_uri_->itemText(i) == openni2_uri_->currentText())
    return QString::fromStdString(currentSpec(openni2_uri_, rig::openNi2CameraSpec("")).openni2_uri);
  return openni2_uri_->currentText().trimmed();
}

QString DevicesPanel::simObject() const { return sim_object_->currentData().toString(); }

void DevicesPanel::setCameraChoice(rig::CameraSpec::Kind kind, const QString& sim_object) {
  camera_kind_->setCurrentIndex(rowOfCameraKind(kind));
  const int i = sim_object_->findData(sim_object);
  if (i >= 0) sim_object_->setCurrentIndex(i);
}

void DevicesPanel::setOpenNi2Uri(const QString& uri) {
  // No URI is the first device found: keep the listed one shown rather than blank the box.
  if (!uri.isEmpty()) openni2_uri_->setEditText(uri);
}

void DevicesPanel::setAddress(const QString& address) { address_->setText(address); }

void DevicesPanel::setPoseChoice(PoseChoice choice) { pose_kind_->setCurrentIndex(static_cast<int>(choice)); }

}  // namespace keyturn::studio
