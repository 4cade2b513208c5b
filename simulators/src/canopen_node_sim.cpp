#include "keyturn/sim/canopen_node_sim.h"

#include <chrono>

namespace keyturn::sim {

CanOpenNodeSim::CanOpenNodeSim(std::unique_ptr<drivers::CanBus> bus, int node_id, bool drive402, CanOpenNodeFaults f)
    : bus_(std::move(bus)), id_(node_id), drive402_(drive402), faults_(f), thread_([this] { loop(); }) {}

CanOpenNodeSim::~CanOpenNodeSim() {
  stop_ = true;
  thread_.join();
}

void CanOpenNodeSim::reply(const std::uint8_t data[8]) {
  drivers::CanFrame f;
  f.id = 0x580 + id_;
  f.dlc = 8;
  for (int i = 0; i < 8; ++i) f.data[i] = data[i];
  bus_->send(f);
}

void CanOpenNodeSim::loop() {
  using Clock = std::chrono::steady_clock;
  auto next_tpdo = Clock::now();
  while (!stop_) {
    if (operational_ && event_timer_ > 0 && Clock::now() >= next_tpdo && !faults_.silent) {
      drivers::CanFrame t;
      t.id = 0x180 + id_;
      t.dlc = 4;
      const auto v = static_cast<std::uint32_t>(position_.load());
      for (int i = 0; i < 4; ++i) t.data[i] = static_cast<std::uint8_t>(v >> (8 * i));
      bus_->send(t);
      next_tpdo = Clock::now() + std::chrono::milliseconds(event_timer_);
    }
    const auto f = bus_->receive(std::chrono::milliseconds(2));
    if (!f || faults_.silent) continue;
    if (f->id == 0x000 && f->dlc >= 2 && (f->data[1] == id_ || f->data[1] == 0)) {
      if (f->data[0] == 0x01) operational_ = true;        // start remote node
      else if (f->data[0] == 0x02 || f->data[0] == 0x80) operational_ = false;  // stop / pre-operational
      continue;
    }
    if (f->id != 0x600u + static_cast<unsigned>(id_) || f->dlc < 8) continue;
    const std::uint16_t index = f->data[1] | (f->data[2] << 8);
    const std::uint8_t sub = f->data[3];
    std::uint8_t r[8] = {0, f->data[1], f->data[2], sub, 0, 0, 0, 0};
    auto abort = [&](std::uint32_t code) {
      r[0] = 0x80;
      for (int i = 0; i < 4; ++i) r[4 + i] = static_cast<std::uint8_t>(code >> (8 * i));
      reply(r);
    };
    const std::uint8_t cs = f->data[0] & 0xE0;
    if (cs == 0x40) {  // upload request
      if (faults_.abort_reads) { abort(0x08000000); continue; }
      const std::uint16_t pos_obj = drive402_ ? 0x6064 : 0x6004;
      if (index == pos_obj && sub == 0) {
        r[0] = 0x43;  // expedited, 4 bytes
        const auto v = static_cast<std::uint32_t>(position_.load());
        for (int i = 0; i < 4; ++i) r[4 + i] = static_cast<std::uint8_t>(v >> (8 * i));
        reply(r);
      } else if (index == 0x1800 && sub == 5) {
        r[0] = 0x4B;  // 2 bytes
        r[4] = event_timer_ & 0xFF;
        r[5] = event_timer_ >> 8;
        reply(r);
      } else {
        abort(0x06020000);
      }
    } else if (cs == 0x20) {  // download request
      if (index == 0x1800 && sub == 5) {
        event_timer_ = static_cast<std::uint16_t>(f->data[4] | (f->data[5] << 8));
        r[0] = 0x60;
        reply(r);
      } else if (index == 0x6004 || index == 0x6064) {
        abort(0x06010002);  // read-only
      } else {
        abort(0x06020000);
      }
    }
  }
}

}  // namespace keyturn::sim
