#pragma once
// The SwissRanger SR4000 through libMesaSR: USB (serial, 0 = first camera) or
// Ethernet (IP), or libmesasr-sim's camera with its configuration passed explicitly. A failed acquisition closes and reopens the camera with
// exponential backoff (reported through the log callback) before giving up.
#include <functional>
#include <memory>
#include <string>

#include "keyturn/drivers/mesasr_library.h"
#include "keyturn/drivers/tof_camera.h"

namespace keyturn::drivers {

struct Sr4000Connection {
  // Simulator: libmesasr-sim's own camera, opened through its KTSIM_OpenWithConfig (mesasr_api.h).
  enum class Kind { Usb, Ethernet, Simulator } kind = Kind::Usb;
  unsigned serial = 0;  // USB: 0 = first camera found
  std::string address;  // Ethernet: IPv4 address
  std::string simulator_config;  // Simulator: its configuration file; empty: the simulator's defaults

  // "usb", "usb:SERIAL", "eth:IP". Throws keyturn::Error.
  static Sr4000Connection parse(const std::string& text);
  std::string describe() const;
};

struct Sr4000Options {
  int reconnect_attempts = 3;
  int backoff_initial_ms = 200;  // doubled per attempt
  std::function<void(const std::string&)> log;  // retries and reconnects are reported here
  std::string name;  // the camera in errors and log lines (default: the connection, "first SR4000 on USB")
};

class Sr4000Camera final : public TofCamera {
 public:
  Sr4000Camera(std::shared_ptr<MesaSrLibrary> lib, Sr4000Connection connection,
               Sr4000Options options = Sr4000Options());
  ~Sr4000Camera() override;

  void configure(const TofSettings& settings) override;
  TofSettings settings() const override;
  TofFrame acquire() override;
  std::string deviceString() const override { return device_; }
  std::uint32_t serial() const override { return serial_; }
  std::uint8_t firmwareVersion() const;
  int reconnects() const { return reconnects_; }

 private:
  void open();
  void close();
  void refreshImageList();
  TofFrame acquireOnce();
  [[noreturn]] void fail(const std::string& what) const;
  std::string name() const;

  std::shared_ptr<MesaSrLibrary> lib_;
  Sr4000Connection connection_;
  Sr4000Options options_;
  SRCAM cam_ = nullptr;
  TofSettings wanted_;
  ImgEntry* images_ = nullptr;
  int image_count_ = 0;
  std::string device_;
  std::uint32_t serial_ = 0;
  std::uint64_t sequence_ = 0;
  int reconnects_ = 0;
};

}  // namespace keyturn::drivers
