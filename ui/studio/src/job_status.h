#pragma once
// The status bar's line for the long jobs (reconstruct, enroll): the stage and a progress bar while
// one runs, then what it made, or its error in one red line.
#include <QWidget>

class QLabel;
class QProgressBar;

namespace keyturn::studio {

class JobStatus : public QWidget {
  Q_OBJECT
 public:
  explicit JobStatus(QWidget* parent = nullptr);
  QString text() const;  // the line shown (plain text)
  bool failed() const { return failed_; }

 public slots:
  void progress(const QString& stage, int done, int total);
  void succeeded(const QString& text);
  void fail(const QString& error);

 private:
  QLabel* label_;
  QProgressBar* bar_;
  QString plain_;
  bool failed_ = false;
};

}  // namespace keyturn::studio
