#include "keyturn/drivers/canopen_pose.h"

#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>

#include "keyturn/core/error.h"
#include "keyturn/core/json_file.h"
#include "keyturn/core/json_integer.h"
#include "keyturn/drivers/retry.h"

namespace keyturn::drivers {
namespace {

std::string hex(std::uint32_t v, int width) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "0x%0*X", width, v);
  return buf;
}

std::uint32_t le32(const std::uint8_t* d) { return d[0] | (d[1] << 8) | (d[2] << 16) | (std::uint32_t(d[3]) << 24); }

}  // namespace

std::uint16_t positionObject(CanOpenAxis::Device d) { return d == CanOpenAxis::Device::Drive402 ? 0x6064 : 0x6004; }

std::string sdoAbortText(std::uint32_t code) {
  switch (code) {
    case 0x05040000: return "SDO protocol timed out";
    case 0x05040001: return "command specifier not valid";
    case 0x06010000: return "unsupported access to an object";
    case 0x06010002: return "attempt to write a read-only object";
    case 0x06020000: return "object does not exist in the object dictionary";
    case 0x06090011: return "sub-index does not exist";
    case 0x08000000: return "general error";
    case 0x08000022: return "data cannot be transferred because of the present device state";
    default: return "abort code " + hex(code, 8);
  }
}

std::vector<CanOpenAxis> CanOpenAxis::loadAll(const std::string& path) {
  const nlohmann::json j = readJsonFile(path, JsonShape::Array);
  if (j.empty()) throw Error(path + ": expected a non-empty list of axes");
  std::vector<CanOpenAxis> out;
  for (std::size_t i = 0; i < j.size(); ++i) {
    const std::string where = path + ": axis " + std::to_string(i);
    try {
      CanOpenAxis a;
      a.name = j[i].at("name").get<std::string>();
      a.node_id = jsonInteger(j[i], "node", 1, 127, where);
      const std::string dev = j[i].value("device", "cia406");
      if (dev == "cia406") a.device = Device::Encoder406;
      else if (dev == "cia402") a.device = Device::Drive402;
      else throw Error(where + ": device must be cia406 or cia402");
      a.scale = j[i].value("scale", 1e-6);
      a.offset = j[i].value("offset", 0.0);
      if (a.name != "x" && a.name != "y" && a.name != "z" && a.name != "turntable")
        throw Error(where + ": name must be x, y, z or turntable");
      out.push_back(a);
    } catch (const Error&) {
      throw;
    } catch (const std::exception& e) {
      throw Error(where + ": " + e.what());
    }
  }
  return out;
}

CanOpenPoseSource::CanOpenPoseSource(std::unique_ptr<CanBus> bus, std::vector<CanOpenAxis> axes, CanOpenOptions o)
    : bus_(std::move(bus)), axes_(std::move(axes)), o_(o) {
  if (axes_.empty()) throw Error(bus_->describe() + ": no CANopen axes configured");
  if (o_.use_tpdo) startTpdo();
}

std::string CanOpenPoseSource::describe() const {
  std::string s = bus_->describe() + " (CANopen nodes";
  for (const auto& a : axes_) s += " " + a.name + "=" + std::to_string(a.node_id);
  return s + ")";
}

std::uint32_t CanOpenPoseSource::sdoUpload(int node, std::uint16_t index, std::uint8_t sub) {
  const std::string what = "reading " + hex(index, 4) + ":" + hex(sub, 2).substr(2) + " from node " + std::to_string(node);
  CanFrame req;
  req.id = 0x600 + node;
  req.dlc = 8;
  req.data[0] = 0x40;
  req.data[1] = index & 0xFF;
  req.data[2] = index >> 8;
  req.data[3] = sub;
  // A lost request or reply is sent again at once (no bus to reconnect); an abort is the node's answer.
  const auto attempt = [&]() -> std::uint32_t {
    bus_->send(req);
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(o_.sdo_timeout_ms);
    while (std::chrono::steady_clock::now() < deadline) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
      const auto f = bus_->receive(std::max(left, std::chrono::milliseconds(1)));
      if (!f) break;
      if (f->id == 0x180u + static_cast<unsigned>(node)) last_tpdo_[node] = le32(f->data);
      if (f->id != 0x580u + static_cast<unsigned>(node) || f->dlc < 8) continue;
      const std::uint16_t idx = f->data[1] | (f->data[2] << 8);
      if (idx != index || f->data[3] != sub) continue;  // a reply to someone else's request
      if (f->data[0] == 0x80)
        throw DeviceRefused(describe() + ": " + what + ": SDO abort " + hex(le32(f->data + 4), 8) + " (" +
                            sdoAbortText(le32(f->data + 4)) + ")");
      if ((f->data[0] & 0xE0) != 0x40)
        throw DeviceRefused(describe() + ": " + what + ": unexpected SDO reply " + hex(f->data[0], 2));
      // Expedited: bits 2..3 give the number of unused bytes when bit 0 (size indicated) is set.
      const int unused = (f->data[0] & 0x01) ? (f->data[0] >> 2) & 3 : 0;
      std::uint32_t v = le32(f->data + 4);
      if (unused > 0) v &= 0xFFFFFFFFu >> (8 * unused);
      return v;
    }
    throw Error("no reply");
  };
  return withRetries(
      RetryPolicy{o_.retries, 0}, attempt, [] {}, [](int, int, const std::string&) {},
      [&](const std::string&) {
        return Error(describe() + ": " + what + ": no SDO reply within " + std::to_string(o_.sdo_timeout_ms) + " ms (" +
                     std::to_string(o_.retries + 1) + " tries); is the node powered and its id right?");
      });
}

void CanOpenPoseSource::sdoDownload(int node, std::uint16_t index, std::uint8_t sub, std::uint32_t value, int bytes) {
  const std::string what = "writing " + hex(index, 4) + ":" + hex(sub, 2).substr(2) + " on node " + std::to_string(node);
  CanFrame req;
  req.id = 0x600 + node;
  req.dlc = 8;
  req.data[0] = static_cast<std::uint8_t>(0x23 | ((4 - bytes) << 2));  // expedited, size indicated
  req.data[1] = index & 0xFF;
  req.data[2] = index >> 8;
  req.data[3] = sub;
  for (int i = 0; i < 4; ++i) req.data[4 + i] = static_cast<std::uint8_t>(value >> (8 * i));
  const auto attempt = [&] {
    bus_->send(req);
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(o_.sdo_timeout_ms);
    while (std::chrono::steady_clock::now() < deadline) {
      const auto f = bus_->receive(std::chrono::milliseconds(5));
      if (!f || f->id != 0x580u + static_cast<unsigned>(node)) continue;
      if (f->data[0] == 0x80)
        throw DeviceRefused(describe() + ": " + what + ": SDO abort " + hex(le32(f->data + 4), 8) + " (" +
                            sdoAbortText(le32(f->data + 4)) + ")");
      if (f->data[0] == 0x60) return;
    }
    throw Error("no reply");
  };
  withRetries(RetryPolicy{o_.retries, 0}, attempt, [] {}, [](int, int, const std::string&) {},
              [&](const std::string&) {
                return Error(describe() + ": " + what + ": no SDO reply within " + std::to_string(o_.sdo_timeout_ms) +
                             " ms");
              });
}

void CanOpenPoseSource::startTpdo() {
  for (const auto& a : axes_) sdoDownload(a.node_id, 0x1800, 5, static_cast<std::uint32_t>(o_.event_timer_ms), 2);
  CanFrame nmt;  // NMT "start remote node" for every axis node
  nmt.id = 0x000;
  nmt.dlc = 2;
  nmt.data[0] = 0x01;
  for (const auto& a : axes_) {
    nmt.data[1] = static_cast<std::uint8_t>(a.node_id);
    bus_->send(nmt);
  }
}

std::uint32_t CanOpenPoseSource::positionBySdo(const CanOpenAxis& a) {
  return sdoUpload(a.node_id, positionObject(a.device), 0);
}

Pose CanOpenPoseSource::read() {
  Pose p;
  if (o_.use_tpdo) {
    // Fresh TPDO1 from every node, within a few event periods.
    last_tpdo_.clear();
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(5 * o_.event_timer_ms + o_.sdo_timeout_ms);
    while (last_tpdo_.size() < axes_.size() && std::chrono::steady_clock::now() < deadline)
      if (const auto f = bus_->receive(std::chrono::milliseconds(o_.event_timer_ms)))
        for (const auto& a : axes_)
          if (f->id == 0x180u + static_cast<unsigned>(a.node_id)) last_tpdo_[a.node_id] = le32(f->data);
    for (const auto& a : axes_)
      if (!last_tpdo_.count(a.node_id))
        throw Error(describe() + ": no TPDO1 from node " + std::to_string(a.node_id) + " (event timer " +
                    std::to_string(o_.event_timer_ms) + " ms)");
  }
  for (const auto& a : axes_) {
    const std::uint32_t raw = o_.use_tpdo ? static_cast<std::uint32_t>(last_tpdo_[a.node_id]) : positionBySdo(a);
    const double counts = a.device == CanOpenAxis::Device::Drive402 ? static_cast<double>(static_cast<std::int32_t>(raw))
                                                                    : static_cast<double>(raw);
    const double v = counts * a.scale + a.offset;
    if (a.name == "x") p.position.x() = v;
    else if (a.name == "y") p.position.y() = v;
    else if (a.name == "z") p.position.z() = v;
    else p.turntable_deg = v;
  }
  p.stamp = std::chrono::system_clock::now();
  return p;
}

}  // namespace keyturn::drivers
