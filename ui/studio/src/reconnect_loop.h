#pragma once
// The one reconnect loop of the studio's device workers (camera and pose source): once a device is
// lost, it tries to open it again every second on the worker's thread, each failure one log line
// ("reconnect: WHY"), until an open succeeds; then it stops and hands over to `recovered`.
#include <QObject>
#include <QString>
#include <QTimer>
#include <functional>

namespace keyturn::studio {

class ReconnectLoop : public QObject {
  Q_OBJECT
 public:
  // reopen: opens the device again, throwing std::exception when it cannot; recovered: after it did.
  ReconnectLoop(std::function<void()> reopen, std::function<void()> recovered, QObject* parent);

  void start();        // the device was lost: try every second from now
  void stop();         // closed by the user, or recovered
  void tryNow();       // one try at once (Reconnect now); stops the loop when it succeeds
  bool running() const { return timer_->isActive(); }

 signals:
  void logLine(const QString& line);

 private:
  void tryOnce();
  std::function<void()> reopen_, recovered_;
  QTimer* timer_;
};

}  // namespace keyturn::studio
