#pragma once
// One long job of the studio (a reconstruction, an enrollment) on a thread of its own, so the
// window keeps drawing: the job reports its stages and steps, and its end (an error as one line).
// One job at a time; the window waits for a running one when it closes.
#include <QObject>
#include <QString>
#include <QThread>
#include <atomic>
#include <functional>

namespace keyturn::studio {

class BackgroundJob : public QObject {
  Q_OBJECT
 public:
  // Runs on the job's thread; a thrown exception's what() becomes the error line.
  using Work = std::function<void(BackgroundJob& job)>;

  explicit BackgroundJob(QObject* parent = nullptr);
  ~BackgroundJob() override;  // waits for a running job

  bool running() const;
  // False (nothing started) while another job runs. `done` runs on the GUI thread after success.
  bool start(const QString& name, Work work, std::function<void()> done);

  // From the work: a stage of `total` steps (0: steps unknown), and one step of it (any thread).
  void stage(const QString& stage, int total);
  void step();

 signals:
  void progressed(const QString& text, int done, int total);
  void finished(const QString& name, const QString& error);  // error "" on success

 private:
  QThread* thread_ = nullptr;
  std::atomic<int> done_{0}, total_{0};
  QString stage_;  // written by the work's thread between steps only
};

}  // namespace keyturn::studio
