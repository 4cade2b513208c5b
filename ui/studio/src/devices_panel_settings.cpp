// The Devices panel's choices kept between runs of the studio (QSettings keys camera/*, pose/*).
#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QLineEdit>
#include <QSettings>
#include <QSpinBox>

#include "devices_panel.h"

namespace keyturn::studio {

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

}  // namespace keyturn::studio
