#pragma once
// The status bar's line for the long jobs (reconstruct, enroll): the stage and a progress bar while
// one runs, with Cancel beside them, then what it made, or its error in one red line.
#include <QWidget>

class QLabel;
class QProgressBar;
class QPushButton;

namespace keyturn::studio {

class JobStatus : public QWidget {
  Q_OBJECT
 public:
  explicit JobStatus(QWidget* parent = nullptr);
  QString text() const;  // the line shown (plain text)
  bool failed() const { return failed_; }

 signals:
  void cancelRequested();  // Cancel clicked while a job runs

 public slots:
  void progress(const QString& stage, int done, int total);
  void succeeded(const QString& text);
  void fail(const QString& error);

 private:
  QLabel* label_;
  void ended();  // no job running: the bar and Cancel hidden
  QProgressBar* bar_;
  QPushButton* cancel_;
  QString plain_;
  bool failed_ = false;
};

}  // namespace keyturn::studio
