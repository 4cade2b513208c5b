#pragma once
// A simulated CANopen node on a CAN bus (the fake bus in tests): a CiA 406
// encoder (0x6004) or CiA 402 drive (0x6064) answering expedited SDO uploads,
// accepting the TPDO1 event timer (0x1800 sub 5), starting on NMT and then
// sending TPDO1 (0x180+id) every event period. Faults: silence, SDO abort.
#include <atomic>
#include <cstdint>
#include <memory>
#include <thread>

#include "keyturn/drivers/can_bus.h"

namespace keyturn::sim {

struct CanOpenNodeFaults {
  bool silent = false;        // never answers
  bool abort_reads = false;   // answers every upload with abort 0x08000000
};

class CanOpenNodeSim {
 public:
  CanOpenNodeSim(std::unique_ptr<drivers::CanBus> bus, int node_id, bool drive402, CanOpenNodeFaults faults = {});
  ~CanOpenNodeSim();
  void setPosition(std::int32_t counts) { position_ = counts; }
  std::uint16_t eventTimerMs() const { return event_timer_; }
  bool operational() const { return operational_; }

 private:
  void loop();
  void reply(const std::uint8_t data[8]);
  std::unique_ptr<drivers::CanBus> bus_;
  int id_;
  bool drive402_;
  CanOpenNodeFaults faults_;
  std::atomic<std::int32_t> position_{0};
  std::atomic<std::uint16_t> event_timer_{0};
  std::atomic<bool> operational_{false}, stop_{false};
  std::thread thread_;
};

}  // namespace keyturn::sim
