#include "reconnect_loop.h"

#include <exception>

namespace keyturn::studio {

ReconnectLoop::ReconnectLoop(std::function<void()> reopen, std::function<void()> recovered, QObject* parent)
    : QObject(parent), reopen_(std::move(reopen)), recovered_(std::move(recovered)), timer_(new QTimer(this)) {
  timer_->setInterval(1000);
  connect(timer_, &QTimer::timeout, this, &ReconnectLoop::tryOnce);
}

void ReconnectLoop::start() { timer_->start(); }

void ReconnectLoop::stop() { timer_->stop(); }

void ReconnectLoop::tryNow() { tryOnce(); }

void ReconnectLoop::tryOnce() {
  try {
    reopen_();
  } catch (const std::exception& e) {
    emit logLine(QString::fromStdString(std::string("reconnect: ") + e.what()));
    return;
  }
  timer_->stop();
  recovered_();
}

}  // namespace keyturn::studio
