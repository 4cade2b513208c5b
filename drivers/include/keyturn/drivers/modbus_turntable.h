#pragma once
// A turntable (or a bare absolute encoder) over Modbus TCP or RTU, with
// libmodbus. Timeouts and dropped connections are retried with exponential
// backoff after reconnecting; a Modbus exception from the device is not
// retried and is named in the error.
#include <functional>
#include <memory>
#include <string>

#include "keyturn/drivers/modbus_profile.h"
#include "keyturn/drivers/pose_source.h"

namespace keyturn::drivers {

struct ModbusEndpoint {
  enum class Kind { Tcp, Rtu } kind = Kind::Tcp;
  std::string host = "127.0.0.1";
  int port = 502;
  std::string device;  // RTU serial device
  int baud = 115200;
  char parity = 'N';
  int data_bits = 8;
  int stop_bits = 1;
  int unit_id = 1;

  // "modbus-tcp:HOST:PORT[@UNIT]" or "modbus-rtu:DEVICE[:BAUD[:8N1]][@UNIT]". Throws keyturn::Error.
  static ModbusEndpoint parse(const std::string& text);
  std::string describe() const;
};

struct ModbusOptions {
  int timeout_ms = 500;
  int retries = 3;
  int backoff_initial_ms = 50;  // doubled per retry
  std::function<void(const std::string&)> log;
};

class ModbusTurntable final : public PoseSource {
 public:
  ModbusTurntable(ModbusEndpoint endpoint, ModbusTurntableProfile profile, ModbusOptions options = ModbusOptions());
  ~ModbusTurntable() override;

  Pose read() override;
  bool canMove() const override { return profile_.motorised(); }
  void moveTo(double turntable_deg) override;
  void home() override;
  void stop() override;
  std::string describe() const override;
  int reconnects() const { return reconnects_; }

 private:
  void connect();
  void disconnect();
  static constexpr int kSnapshotSpan = 16;  // registers read in one request for position + status
  void readBlock(ModbusRegister::Function function, int address, int n, std::uint16_t* regs);
  std::uint32_t readRaw(const ModbusRegister& r);
  void writeRaw(const ModbusRegister& r, std::int64_t value);
  void writeOne(const ModbusWrite& w);
  template <typename F>
  auto withRetry(const char* what, F&& f) -> decltype(f());

  ModbusEndpoint endpoint_;
  ModbusTurntableProfile profile_;
  ModbusOptions options_;
  struct Ctx;
  std::unique_ptr<Ctx> ctx_;
  int reconnects_ = 0;
};

// Names a libmodbus errno: Modbus exception codes by number and meaning.
std::string modbusErrorText(int err);

}  // namespace keyturn::drivers
