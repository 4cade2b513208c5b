#include "keyturn/drivers/can_bus.h"

#include <linux/can.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "keyturn/core/error.h"

namespace keyturn::drivers {

bool SocketCanBus::available(std::string* why) {
  const int fd = ::socket(PF_CAN, SOCK_RAW, CAN_RAW);
  if (fd < 0) {
    if (why) *why = std::string("this kernel has no SocketCAN (socket(PF_CAN) failed: ") + std::strerror(errno) + ")";
    return false;
  }
  ::close(fd);
  return true;
}

SocketCanBus::SocketCanBus(const std::string& iface) : iface_(iface) {
  std::string why;
  if (!available(&why)) throw Error(describe() + ": " + why);
  fd_ = ::socket(PF_CAN, SOCK_RAW, CAN_RAW);
  ifreq ifr{};
  if (iface.size() >= sizeof ifr.ifr_name) throw Error(describe() + ": interface name too long");
  std::strncpy(ifr.ifr_name, iface.c_str(), sizeof ifr.ifr_name - 1);
  if (::ioctl(fd_, SIOCGIFINDEX, &ifr) < 0) {
    const int e = errno;
    ::close(fd_);
    throw Error(describe() + ": no such CAN interface (" + std::strerror(e) + "); is it up? ip link set " + iface + " up");
  }
  sockaddr_can addr{};
  addr.can_family = AF_CAN;
  addr.can_ifindex = ifr.ifr_ifindex;
  if (::bind(fd_, reinterpret_cast<sockaddr*>(&addr), sizeof addr) < 0) {
    const int e = errno;
    ::close(fd_);
    throw Error(describe() + ": cannot bind: " + std::strerror(e));
  }
}

SocketCanBus::~SocketCanBus() {
  if (fd_ >= 0) ::close(fd_);
}

void SocketCanBus::send(const CanFrame& f) {
  can_frame c{};
  c.can_id = f.id & CAN_SFF_MASK;
  c.can_dlc = f.dlc;
  std::memcpy(c.data, f.data, 8);
  if (::write(fd_, &c, sizeof c) != static_cast<ssize_t>(sizeof c))
    throw Error(describe() + ": send failed: " + std::strerror(errno));
}

std::optional<CanFrame> SocketCanBus::receive(std::chrono::milliseconds timeout) {
  pollfd p{fd_, POLLIN, 0};
  if (::poll(&p, 1, static_cast<int>(timeout.count())) <= 0) return std::nullopt;
  can_frame c{};
  if (::read(fd_, &c, sizeof c) != static_cast<ssize_t>(sizeof c)) throw Error(describe() + ": receive failed: " + std::strerror(errno));
  if (c.can_id & (CAN_EFF_FLAG | CAN_RTR_FLAG | CAN_ERR_FLAG)) return std::nullopt;  // not a data frame for us
  CanFrame f;
  f.id = c.can_id & CAN_SFF_MASK;
  f.dlc = c.can_dlc;
  std::memcpy(f.data, c.data, 8);
  return f;
}

class FakeCanEndpoint final : public CanBus {
 public:
  FakeCanEndpoint(std::shared_ptr<FakeCanHub> hub, std::shared_ptr<FakeCanHub::Queue> q, std::string name)
      : hub_(std::move(hub)), q_(std::move(q)), name_(std::move(name)) {}
  void send(const CanFrame& f) override { hub_->deliver(q_.get(), f); }
  std::optional<CanFrame> receive(std::chrono::milliseconds timeout) override {
    std::unique_lock<std::mutex> lock(hub_->mutex_);
    if (!hub_->cv_.wait_for(lock, timeout, [&] { return !q_->frames.empty(); })) return std::nullopt;
    CanFrame f = q_->frames.front();
    q_->frames.pop_front();
    return f;
  }
  std::string describe() const override { return "fake-can " + name_; }

 private:
  std::shared_ptr<FakeCanHub> hub_;
  std::shared_ptr<FakeCanHub::Queue> q_;
  std::string name_;
};

std::unique_ptr<CanBus> FakeCanHub::endpoint(std::string name) {
  auto q = std::make_shared<Queue>();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    queues_.push_back(q);
  }
  return std::make_unique<FakeCanEndpoint>(shared_from_this(), q, std::move(name));
}

void FakeCanHub::deliver(const Queue* from, const CanFrame& f) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    for (auto& q : queues_)
      if (q.get() != from) q->frames.push_back(f);
  }
  cv_.notify_all();
}

}  // namespace keyturn::drivers
