#pragma once
// Capture: where (dataset folder), what (class, instance), how (elevation,
// step, range); start / pause / resume / stop; progress with ETA and a
// thumbnail of every view written; then Reconstruct and Enroll… of the captured object.
#include <QElapsedTimer>
#include <QWidget>

#include "frame_types.h"
#include "keyturn/rig/capture.h"

class QDoubleSpinBox;
class QLabel;
class QLineEdit;
class QListWidget;
class QProgressBar;
class QPushButton;
class QSettings;

namespace keyturn::studio {

class CapturePanel : public QWidget {
  Q_OBJECT
 public:
  explicit CapturePanel(QWidget* parent = nullptr);

  std::string dataset() const;
  std::string calibration() const;  // axis calibration file, "" = none
  rig::CaptureOptions options() const;
  void setObject(const QString& cls, const QString& instance);
  void setDataset(const QString& folder);
  void save(QSettings& s) const;
  void restore(const QSettings& s);
  bool running() const { return state_ == State::Running; }
  void startFromOutside();  // as if Start were clicked

 public slots:
  void progress(int done, int skipped, int total, double angle, keyturn::studio::FramePtr frame, const QString& view);
  void finished(int written, int skipped, bool stopped, const QString& error);

 signals:
  void start();   // the window checks for existing views, then starts
  void pause();
  void resume();
  void stop();
  void reconstruct();  // the captured object's views joined into its model
  void enroll();       // the reconstructed object added to the model

 private:
  enum class State { Idle, Running, Pausing, Paused, Stopping } state_ = State::Idle;
  void setState(State s);

  QLineEdit *folder_, *cls_, *instance_, *elevation_label_, *calibration_;
  QDoubleSpinBox *elevation_, *step_, *start_deg_, *range_;
  QPushButton *start_, *pause_, *stop_, *reconstruct_, *enroll_;
  QProgressBar* bar_;
  QLabel* eta_;
  QListWidget* thumbnails_;
  QElapsedTimer clock_;
  int first_done_ = -1;
};

}  // namespace keyturn::studio
