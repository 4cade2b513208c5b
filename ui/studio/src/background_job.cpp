#include "background_job.h"

#include <exception>
#include <memory>

namespace keyturn::studio {

BackgroundJob::BackgroundJob(QObject* parent) : QObject(parent) {}

BackgroundJob::~BackgroundJob() {
  if (!thread_) return;
  thread_->wait();
  delete thread_;
}

bool BackgroundJob::running() const { return thread_ && !thread_->isFinished(); }

bool BackgroundJob::start(const QString& name, Work work, std::function<void()> done) {
  if (running()) return false;
  if (thread_) thread_->deleteLater();
  auto error = std::make_shared<QString>();
  cancelled_ = false;
  thread_ = QThread::create([this, name, work = std::move(work), error] {
    try {
      work(*this);
    } catch (const JobCancelled&) {
      *error = tr("cancelled");
    } catch (const std::exception& e) {
      *error = QString::fromUtf8(e.what()).split('\n').front();
    } catch (...) {
      *error = tr("%1 failed").arg(name);
    }
  });
  connect(thread_, &QThread::finished, this, [this, name, error, done = std::move(done)] {
    if (error->isEmpty() && done) {
      try {
        done();
      } catch (const std::exception& e) {
        *error = QString::fromUtf8(e.what()).split('\n').front();
      }
    }
    emit finished(name, *error);
  });
  stage(name, 0);
  thread_->start();
  return true;
}

void BackgroundJob::cancel() {
  if (running()) cancelled_ = true;
}

void BackgroundJob::throwIfCancelled() const {
  if (cancelled_) throw JobCancelled();
}

void BackgroundJob::stage(const QString& stage, int total) {
  throwIfCancelled();
  stage_ = stage;
  done_ = 0;
  total_ = total;
  emit progressed(stage, 0, total);
}

void BackgroundJob::step() {
  throwIfCancelled();
  const int done = ++done_;
  emit progressed(stage_, done, total_);
}

}  // namespace keyturn::studio
