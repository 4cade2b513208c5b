#pragma once
// A CAN transport: classic 11-bit frames. SocketCAN (PF_CAN raw socket, an
// interface by name) on Linux hosts with CAN; an in-process fake bus for tests,
// since this project's build machines have no CAN support at all (not even vcan).
#include <chrono>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <condition_variable>
#include <optional>
#include <string>
#include <vector>

namespace keyturn::drivers {

struct CanFrame {
  std::uint32_t id = 0;  // 11-bit identifier
  std::uint8_t dlc = 0;
  std::uint8_t data[8] = {};
};

class CanBus {
 public:
  virtual ~CanBus() = default;
  virtual void send(const CanFrame& frame) = 0;  // throws keyturn::Error
  virtual std::optional<CanFrame> receive(std::chrono::milliseconds timeout) = 0;
  virtual std::string describe() const = 0;
};

class SocketCanBus final : public CanBus {
 public:
  explicit SocketCanBus(const std::string& interface);  // throws keyturn::Error naming why
  ~SocketCanBus() override;
  void send(const CanFrame& frame) override;
  std::optional<CanFrame> receive(std::chrono::milliseconds timeout) override;
  std::string describe() const override { return "can " + iface_; }
  // Whether this kernel offers PF_CAN at all (and why not).
  static bool available(std::string* why = nullptr);

 private:
  std::string iface_;
  int fd_ = -1;
};

// Every endpoint of a FakeCanHub receives the frames the others send, as on a
// real bus (no echo of its own frames).
class FakeCanHub : public std::enable_shared_from_this<FakeCanHub> {
 public:
  static std::shared_ptr<FakeCanHub> create() { return std::shared_ptr<FakeCanHub>(new FakeCanHub()); }
  std::unique_ptr<CanBus> endpoint(std::string name);

 private:
  FakeCanHub() = default;
  friend class FakeCanEndpoint;
  struct Queue {
    std::deque<CanFrame> frames;
  };
  void deliver(const Queue* from, const CanFrame& f);
  std::mutex mutex_;
  std::condition_variable cv_;
  std::vector<std::shared_ptr<Queue>> queues_;
};

}  // namespace keyturn::drivers
