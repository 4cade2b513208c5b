#pragma once
// One long job of the studio (a reconstruction, an enrollment) on a thread of its own, so the
// window keeps drawing: the job reports its stages and steps, and its end (an error as one line).
// One job at a time; the window waits for a running one when it closes. A job is cancelled at its
// next stage or step: the work is ended there by an exception, so what it would have written at
// its end is not written, and `finished` reports the error "cancelled".
#include <QObject>
#include <QString>
#include <QThread>
#include <atomic>
#include <exception>
#include <functional>

namespace keyturn::studio {

// What stage() and step() throw in a cancelled job (not a keyturn::Error: nothing to report per view).
struct JobCancelled : std::exception {
  const char* what() const noexcept override { return "cancelled"; }
};

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
  // Both throw JobCancelled once cancel() was called.
  void stage(const QString& stage, int total);
  void step();

  // Asks the running job to stop at its next stage or step (any thread; nothing when none runs).
  void cancel();
  bool cancelling() const { return cancelled_; }

 signals:
  void progressed(const QString& text, int done, int total);
  void finished(const QString& name, const QString& error);  // error "" on success

 private:
  QThread* thread_ = nullptr;
  void throwIfCancelled() const;
  std::atomic<int> done_{0}, total_{0};
  std::atomic<bool> cancelled_{false};
  QString stage_;  // written by the work's thread between steps only
};

}  // namespace keyturn::studio
