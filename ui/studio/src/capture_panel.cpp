#include "capture_panel.h"

#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QFormLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QListWidget>
#include <QProgressBar>
#include <QPushButton>
#include <QSettings>
#include <QVBoxLayout>

#include "image_panel.h"

namespace keyturn::studio {
namespace {

QDoubleSpinBox* degrees(double lo, double hi, double value) {
  auto* s = new QDoubleSpinBox;
  s->setRange(lo, hi);
  s->setDecimals(1);
  s->setValue(value);
  s->setSuffix("°");
  return s;
}

QString clockText(double s) {
  const int t = static_cast<int>(s + 0.5);
  return QString("%1:%2").arg(t / 60).arg(t % 60, 2, 10, QChar('0'));
}

}  // namespace

CapturePanel::CapturePanel(QWidget* parent) : QWidget(parent) {
  auto* layout = new QHBoxLayout(this);
  auto* setup = new QGroupBox(tr("Sequence"));
  auto* form = new QFormLayout(setup);
  folder_ = new QLineEdit;
  folder_->setObjectName("captureFolder");
  auto* browse = new QPushButton(tr("…"));
  auto* folder_row = new QHBoxLayout;
  folder_row->addWidget(folder_, 1);
  folder_row->addWidget(browse);
  form->addRow(tr("Dataset"), folder_row);
  cls_ = new QLineEdit("mug");
  instance_ = new QLineEdit("ycb_025_mug");
  auto* what = new QHBoxLayout;
  what->addWidget(cls_);
  what->addWidget(instance_);
  form->addRow(tr("Class / instance"), what);
  elevation_label_ = new QLineEdit("30");
  elevation_label_->setMaximumWidth(60);
  elevation_ = degrees(-90, 90, 30);
  auto* elev = new QHBoxLayout;
  elev->addWidget(elevation_label_);
  elev->addWidget(elevation_);
  form->addRow(tr("Elevation label / angle"), elev);
  step_ = degrees(0.1, 180, 5);
  step_->setObjectName("captureStep");
  start_deg_ = degrees(0, 359.9, 0);
  range_ = degrees(0.1, 360, 360);
  range_->setObjectName("captureRange");
  auto* angles = new QHBoxLayout;
  angles->addWidget(new QLabel(tr("step")));
  angles->addWidget(step_);
  angles->addWidget(new QLabel(tr("from")));
  angles->addWidget(start_deg_);
  angles->addWidget(new QLabel(tr("over")));
  angles->addWidget(range_);
  form->addRow(tr("Turntable"), angles);
  calibration_ = new QLineEdit;
  calibration_->setObjectName("captureCalibration");
  calibration_->setPlaceholderText(tr("axis calibration (keyturn calibrate-axis); simulated rig: exact"));
  calibration_->setToolTip(tr("Gives every view its camera ← turntable transform; copied into the dataset"));
  auto* calib_browse = new QPushButton(tr("…"));
  auto* calib_row = new QHBoxLayout;
  calib_row->addWidget(calibration_, 1);
  calib_row->addWidget(calib_browse);
  form->addRow(tr("Calibration"), calib_row);
  layout->addWidget(setup);
  connect(calib_browse, &QPushButton::clicked, this, [this] {
    const QString f = QFileDialog::getOpenFileName(this, tr("Axis calibration"), calibration_->text(), "JSON (*.json)");
    if (!f.isEmpty()) calibration_->setText(f);
  });

  auto* run = new QGroupBox(tr("Run"));
  auto* rl = new QVBoxLayout(run);
  auto* buttons = new QHBoxLayout;
  start_ = new QPushButton(tr("Start capture"));
  start_->setObjectName("captureStart");
  start_->setShortcut(QKeySequence(Qt::CTRL | Qt::Key_R));
  start_->setToolTip(tr("Start, or resume a paused capture (Ctrl+R)"));
  pause_ = new QPushButton(tr("Pause"));
  pause_->setObjectName("capturePause");
  stop_ = new QPushButton(tr("Stop"));
  stop_->setObjectName("captureStop");
  buttons->addWidget(start_);
  buttons->addWidget(pause_);
  buttons->addWidget(stop_);
  rl->addLayout(buttons);
  bar_ = new QProgressBar;
  bar_->setObjectName("captureProgress");
  bar_->setRange(0, 1);
  bar_->setValue(0);
  bar_->setFormat(tr("no capture yet"));
  rl->addWidget(bar_);
  eta_ = new QLabel(tr("idle"));
  eta_->setObjectName("captureEta");
  rl->addWidget(eta_);
  thumbnails_ = new QListWidget;
  thumbnails_->setObjectName("captureThumbnails");
  thumbnails_->setViewMode(QListView::IconMode);
  thumbnails_->setFlow(QListView::LeftToRight);
  thumbnails_->setWrapping(false);
  thumbnails_->setIconSize(QSize(88, 72));
  thumbnails_->setMinimumHeight(110);
  rl->addWidget(thumbnails_);
  // Beside Start / Pause / Stop, not in a row of their own: the capture dock's height is the window's
  // (theWindowFitsA1600By1000Screen).
  reconstruct_ = new QPushButton(tr("Reconstruct"));
  reconstruct_->setObjectName("captureReconstruct");
  reconstruct_->setToolTip(tr("Join the captured object's views into its model and show its mesh (keyturn reconstruct)"));
  enroll_ = new QPushButton(tr("Enroll…"));
  enroll_->setObjectName("captureEnroll");
  enroll_->setToolTip(tr("Add the reconstructed object to the model and recognise with the new model (keyturn enroll)"));
  buttons->addSpacing(12);
  buttons->addWidget(reconstruct_);
  buttons->addWidget(enroll_);
  layout->addWidget(run, 1);
  connect(reconstruct_, &QPushButton::clicked, this, &CapturePanel::reconstruct);
  connect(enroll_, &QPushButton::clicked, this, &CapturePanel::enroll);

  connect(browse, &QPushButton::clicked, this, [this] {
    const QString d = QFileDialog::getExistingDirectory(this, tr("Dataset folder"), folder_->text());
    if (!d.isEmpty()) folder_->setText(d);
  });
  connect(start_, &QPushButton::clicked, this, [this] {
    if (state_ == State::Paused) {
      setState(State::Running);
      emit resume();
    } else if (state_ == State::Idle) {
      thumbnails_->clear();
      first_done_ = -1;
      emit start();
    }
  });
  connect(pause_, &QPushButton::clicked, this, [this] {
    if (state_ != State::Running) return;
    setState(State::Pausing);
    emit pause();
  });
  connect(stop_, &QPushButton::clicked, this, [this] {
    if (state_ == State::Paused) {
      setState(State::Idle);
      eta_->setText(tr("stopped"));
    } else if (state_ == State::Running || state_ == State::Pausing) {
      setState(State::Stopping);
      emit stop();
    }
  });
  setState(State::Idle);
}

void CapturePanel::setState(State s) {
  state_ = s;
  start_->setEnabled(s == State::Idle || s == State::Paused);
  start_->setText(s == State::Paused ? tr("Resume") : tr("Start capture"));
  pause_->setEnabled(s == State::Running);
  stop_->setEnabled(s != State::Idle);
  reconstruct_->setEnabled(s == State::Idle);
  enroll_->setEnabled(s == State::Idle);
  for (QWidget* w : std::initializer_list<QWidget*>{folder_, cls_, instance_, elevation_label_, elevation_, step_,
                                                    start_deg_, range_, calibration_})
    w->setEnabled(s == State::Idle);
  if (s == State::Running) clock_.start();
}

std::string CapturePanel::dataset() const { return folder_->text().trimmed().toStdString(); }
std::string CapturePanel::calibration() const { return calibration_->text().trimmed().toStdString(); }

rig::CaptureOptions CapturePanel::options() const {
  rig::CaptureOptions o;
  o.cls = cls_->text().trimmed().toStdString();
  o.instance = instance_->text().trimmed().toStdString();
  o.elevation_label = elevation_label_->text().trimmed().toStdString();
  o.elevation_deg = elevation_->value();
  o.step_deg = step_->value();
  o.start_deg = start_deg_->value();
  o.range_deg = range_->value();
  return o;
}

void CapturePanel::setObject(const QString& cls, const QString& instance) {
  if (state_ != State::Idle) return;
  cls_->setText(cls);
  instance_->setText(instance);
}

void CapturePanel::startFromOutside() { start_->click(); }

void CapturePanel::setDataset(const QString& folder) { folder_->setText(folder); }

void CapturePanel::save(QSettings& s) const {
  s.setValue("capture/folder", folder_->text());
  s.setValue("capture/elevation_label", elevation_label_->text());
  s.setValue("capture/elevation", elevation_->value());
  s.setValue("capture/step", step_->value());
  s.setValue("capture/range", range_->value());
  s.setValue("capture/calibration", calibration_->text());
}

void CapturePanel::restore(const QSettings& s) {
  if (s.contains("capture/folder")) folder_->setText(s.value("capture/folder").toString());
  elevation_label_->setText(s.value("capture/elevation_label", "30").toString());
  elevation_->setValue(s.value("capture/elevation", 30.0).toDouble());
  step_->setValue(s.value("capture/step", 5.0).toDouble());
  range_->setValue(s.value("capture/range", 360.0).toDouble());
  calibration_->setText(s.value("capture/calibration").toString());
}

void CapturePanel::progress(int done, int skipped, int total, double angle, FramePtr frame, const QString& view) {
  if (state_ == State::Idle) setState(State::Running);
  bar_->setFormat(tr("%v / %m views"));
  bar_->setMaximum(total);
  bar_->setValue(done + skipped);
  if (first_done_ < 0) {
    first_done_ = done + skipped;
    clock_.restart();
  }
  const int taken = done + skipped - first_done_;
  QString text = QString("%1° · %2 written, %3 already there").arg(angle, 0, 'f', 1).arg(done).arg(skipped);
  if (taken > 0) {
    const double per_view = clock_.elapsed() / 1000.0 / taken;
    text += QString(" · %1 s per view · ETA %2").arg(per_view, 0, 'f', 2).arg(clockText(per_view * (total - done - skipped)));
  }
  eta_->setText(text);
  if (frame) {
    ImageScale scale;
    const double mpc = drivers::nonAmbiguousRange(frame->settings.modulation_frequency) / 65535.0;
    const QImage img = distanceImage(frame->distance, static_cast<int>(frame->width), static_cast<int>(frame->height), mpc, &scale);
    auto* item = new QListWidgetItem(QIcon(QPixmap::fromImage(img)), QString("%1°").arg(angle, 0, 'f', 1));
    item->setToolTip(view);
    thumbnails_->addItem(item);
    thumbnails_->scrollToItem(item);
  }
}

void CapturePanel::finished(int written, int skipped, bool stopped, const QString& error) {
  if (!error.isEmpty()) {
    setState(State::Idle);
    eta_->setText(QString("<span style='color:#c0392b'>capture failed: %1</span>").arg(error.toHtmlEscaped()));
    return;
  }
  if (stopped && state_ == State::Pausing) {
    setState(State::Paused);
    eta_->setText(tr("paused after %1 views: Resume skips the views already written").arg(bar_->value()));
    return;
  }
  setState(State::Idle);
  eta_->setText(stopped ? tr("stopped at %1 of %2 views").arg(bar_->value()).arg(bar_->maximum())
                        : tr("done: %1 views written, %2 were already there").arg(written).arg(skipped));
}

}  // namespace keyturn::studio
