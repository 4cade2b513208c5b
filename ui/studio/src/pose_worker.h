#pragma once
// The pose source's own thread: a 10 Hz readout, motion commands (jog, home,
// move to, stop), and reconnection when the device stops answering. The source
// is shared, behind a lock, with capture sequences on the camera's thread.
#include <QObject>
#include <QTimer>

#include "reconnect_loop.h"
#include <memory>
#include <optional>

#include "keyturn/studio/rig_factory.h"

namespace keyturn::studio {

class PoseWorker : public QObject {
  Q_OBJECT
 public:
  explicit PoseWorker(RigFactory& factory);
  ~PoseWorker() override;

  // Called in the worker's thread.
  void open(const std::optional<rig::PoseSpec>& spec);  // none: no pose source
  void close();
  void jog(double delta_deg);
  void home();
  void moveTo(double deg);
  void stopMotion();

 signals:
  void opened(QString device, bool can_move, std::shared_ptr<keyturn::drivers::PoseSource> source);
  void closed();
  void pose(double turntable_deg, double x, double y, double z, bool moving, bool in_position);
  void openFailed(QString message);
  void failed(QString message);
  void recovered(QString device);
  void logLine(QString line);

 private:
  void poll();
  void command(const char* what, const std::function<void(drivers::PoseSource&)>& f);
  void connectSource();  // spec_; throws

  RigFactory& factory_;
  std::optional<rig::PoseSpec> spec_;
  std::shared_ptr<drivers::PoseSource> source_;
  QTimer* poll_ = nullptr;
  ReconnectLoop* reconnect_ = nullptr;
  double last_deg_ = 0;
};

}  // namespace keyturn::studio
