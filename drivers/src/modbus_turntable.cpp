#include "keyturn/drivers/modbus_turntable.h"

#include <modbus/modbus.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <thread>

#include "keyturn/core/checked_integer.h"
#include "keyturn/core/error.h"
#include "keyturn/drivers/retry.h"

namespace keyturn::drivers {

struct ModbusTurntable::Ctx {
  modbus_t* m = nullptr;
  ~Ctx() {
    if (m) {
      modbus_close(m);
      modbus_free(m);
    }
  }
};

namespace {

// A device's "no" (a Modbus exception) will not change on retry; anything else may.
bool isModbusException(int err) { return err > MODBUS_ENOBASE && err <= MODBUS_ENOBASE + 11; }

}  // namespace

std::string modbusErrorText(int err) {
  if (isModbusException(err))
    return "Modbus exception " + std::to_string(err - MODBUS_ENOBASE) + " (" + modbus_strerror(err) + ")";
  if (err == ETIMEDOUT) return "no reply (timed out)";
  return modbus_strerror(err);
}

ModbusEndpoint ModbusEndpoint::parse(const std::string& text) {
  ModbusEndpoint e;
  std::string rest;
  if (text.rfind("modbus-tcp:", 0) == 0) {
    e.kind = Kind::Tcp;
    rest = text.substr(11);
  } else if (text.rfind("modbus-rtu:", 0) == 0) {
    e.kind = Kind::Rtu;
    rest = text.substr(11);
  } else {
    throw Error("pose source '" + text + "': expected modbus-tcp:HOST:PORT or modbus-rtu:DEVICE");
  }
  if (const auto at = rest.rfind('@'); at != std::string::npos) {
    // Parsed whole, not with atoi: "@4294967297" must not wrap to unit 1.
    const auto id = parseIntegerIn(std::string_view(rest).substr(at + 1), 1, 247);
    if (!id) throw Error("pose source '" + text + "': unit id must be 1..247");
    e.unit_id = *id;
    rest.resize(at);
  }
  if (e.kind == Kind::Tcp) {
    const auto colon = rest.rfind(':');
    if (colon == std::string::npos) throw Error("pose source '" + text + "': expected HOST:PORT");
    e.host = rest.substr(0, colon);
    const auto port = parseIntegerIn(std::string_view(rest).substr(colon + 1), 1, 65535);
    if (e.host.empty() || !port) throw Error("pose source '" + text + "': bad host or port");
    e.port = *port;
  } else {
    // DEVICE[:BAUD[:8N1]]
    std::vector<std::string> parts;
    std::size_t start = 0;
    for (std::size_t c; (c = rest.find(':', start)) != std::string::npos; start = c + 1)
      parts.push_back(rest.substr(start, c - start));
    parts.push_back(rest.substr(start));
    e.device = parts[0];
    if (e.device.empty()) throw Error("pose source '" + text + "': no serial device");
    if (parts.size() > 1) e.baud = parseIntegerIn(parts[1], 1, 10000000).value_or(0);
    if (parts.size() > 2) {
      const std::string& f = parts[2];
      if (f.size() != 3 || (f[1] != 'N' && f[1] != 'E' && f[1] != 'O'))
        throw Error("pose source '" + text + "': frame format like 8N1 expected");
      e.data_bits = f[0] - '0';
      e.parity = f[1];
      e.stop_bits = f[2] - '0';
    }
    if (e.baud <= 0) throw Error("pose source '" + text + "': bad baud rate");
  }
  return e;
}

std::string ModbusEndpoint::describe() const {
  if (kind == Kind::Tcp) return "modbus-tcp " + host + ":" + std::to_string(port) + " unit " + std::to_string(unit_id);
  return "modbus-rtu " + device + " " + std::to_string(baud) + " " + std::to_string(data_bits) + parity +
         std::to_string(stop_bits) + " unit " + std::to_string(unit_id);
}

ModbusTurntable::ModbusTurntable(ModbusEndpoint endpoint, ModbusTurntableProfile profile, ModbusOptions options)
    : endpoint_(std::move(endpoint)), profile_(std::move(profile)), options_(std::move(options)) {
  connect();
}

ModbusTurntable::~ModbusTurntable() = default;

std::string ModbusTurntable::describe() const { return endpoint_.describe() + " (" + profile_.name + ")"; }

void ModbusTurntable::connect() {
  auto c = std::make_unique<Ctx>();
  c->m = endpoint_.kind == ModbusEndpoint::Kind::Tcp
             ? modbus_new_tcp(endpoint_.host.c_str(), endpoint_.port)
             : modbus_new_rtu(endpoint_.device.c_str(), endpoint_.baud, endpoint_.parity, endpoint_.data_bits,
                              endpoint_.stop_bits);
  if (!c->m) throw Error(describe() + ": " + modbus_strerror(errno));
  modbus_set_slave(c->m, endpoint_.unit_id);
  modbus_set_response_timeout(c->m, options_.timeout_ms / 1000, (options_.timeout_ms % 1000) * 1000);
  if (modbus_connect(c->m) == -1) throw Error(describe() + ": cannot connect: " + modbus_strerror(errno));
  ctx_ = std::move(c);
}

void ModbusTurntable::disconnect() { ctx_.reset(); }

template <typename F>
auto ModbusTurntable::withRetry(const char* what, F&& f) -> decltype(f()) {
  return withRetries(
      RetryPolicy{options_.retries, options_.backoff_initial_ms},
      [&] {
        if (!ctx_) throw Error("not connected");  // the last reconnect failed
        return f();
      },
      [&] {
        disconnect();
        connect();
        ++reconnects_;
      },
      [&](int k, int wait, const std::string& last) {
        if (options_.log)
          options_.log(describe() + ": " + what + ": " + last + "; retrying in " + std::to_string(wait) + " ms (attempt " +
                       std::to_string(k) + " of " + std::to_string(options_.retries) + ")");
      },
      [&](const std::string& last) {
        return Error(describe() + ": " + what + " failed after " + std::to_string(options_.retries) + " retries: " + last);
      });
}

void ModbusTurntable::readBlock(ModbusRegister::Function function, int address, int n, std::uint16_t* regs) {
  const int rc = function == ModbusRegister::Function::Input ? modbus_read_input_registers(ctx_->m, address, n, regs)
                                                             : modbus_read_registers(ctx_->m, address, n, regs);
  if (rc != n) {
    const int err = errno;
    const std::string msg = "reading register " + std::to_string(address) + ": " + modbusErrorText(err);
    if (isModbusException(err)) throw DeviceRefused(describe() + ": " + msg);
    throw Error(msg);
  }
}

namespace {
std::uint32_t decodeRegister(const ModbusRegister& r, const std::uint16_t* regs) {
  if (r.bits == 16) return regs[0];
  return r.high_word_first ? (std::uint32_t(regs[0]) << 16) | regs[1] : (std::uint32_t(regs[1]) << 16) | regs[0];
}
}  // namespace

std::uint32_t ModbusTurntable::readRaw(const ModbusRegister& r) {
  std::uint16_t regs[2] = {0, 0};
  readBlock(r.function, r.address, r.bits / 16, regs);
  return decodeRegister(r, regs);
}

void ModbusTurntable::writeRaw(const ModbusRegister& r, std::int64_t value) {
  const auto v = static_cast<std::uint32_t>(value);
  int rc;
  if (r.bits == 16) {
    rc = modbus_write_register(ctx_->m, r.address, static_cast<std::uint16_t>(v)) == 1 ? 1 : -1;
  } else {
    const std::uint16_t hi = static_cast<std::uint16_t>(v >> 16), lo = static_cast<std::uint16_t>(v & 0xFFFF);
    const std::uint16_t regs[2] = {r.high_word_first ? hi : lo, r.high_word_first ? lo : hi};
    rc = modbus_write_registers(ctx_->m, r.address, 2, regs) == 2 ? 1 : -1;
  }
  if (rc != 1) {
    const int err = errno;
    const std::string msg = "writing register " + std::to_string(r.address) + ": " + modbusErrorText(err);
    if (isModbusException(err)) throw DeviceRefused(describe() + ": " + msg);
    throw Error(msg);
  }
}

void ModbusTurntable::writeOne(const ModbusWrite& w) {
  ModbusRegister r;
  r.address = w.address;
  writeRaw(r, w.value);
}

Pose ModbusTurntable::read() {
  return withRetry("read", [&] {
    // Position and status must describe the same instant: a position read while the table still moved,
    // paired with a status read after it arrived, would report "in position" at the wrong angle. When the
    // status sits near the position (holding registers) one request reads both; otherwise the status is
    // read first, so "in position" always comes with a position taken after it.
    const ModbusRegister& pos = profile_.position;
    std::uint32_t raw = 0, status_bits = 0;
    if (profile_.status) {
      const int status_at = profile_.status->address, pos_words = pos.bits / 16;
      const int lo = std::min(pos.address, status_at), hi = std::max(pos.address + pos_words - 1, status_at);
      if (pos.function == ModbusRegister::Function::Holding && hi - lo < kSnapshotSpan) {
        std::uint16_t regs[kSnapshotSpan] = {};
        readBlock(ModbusRegister::Function::Holding, lo, hi - lo + 1, regs);
        raw = decodeRegister(pos, regs + (pos.address - lo));
        status_bits = regs[status_at - lo];
      } else {
        ModbusRegister s;
        s.address = status_at;
        status_bits = readRaw(s);
        raw = readRaw(pos);
      }
    } else {
      raw = readRaw(pos);
    }
    Pose p;
    const double counts = pos.is_signed ? (pos.bits == 32 ? static_cast<double>(static_cast<std::int32_t>(raw))
                                                          : static_cast<double>(static_cast<std::int16_t>(raw)))
                                        : static_cast<double>(raw);
    p.turntable_deg = profile_.countsToDegrees(counts);
    if (profile_.status) {
      p.moving = (status_bits >> profile_.status->moving_bit) & 1u;
      p.in_position = (status_bits >> profile_.status->in_position_bit) & 1u;
    }
    p.stamp = std::chrono::system_clock::now();
    return p;
  });
}

void ModbusTurntable::moveTo(double deg) {
  if (!profile_.motorised()) unsupported("move");
  const double wrapped = std::fmod(std::fmod(deg, 360.0) + 360.0, 360.0);
  withRetry("move", [&] {
    writeRaw(*profile_.target, std::llround(profile_.degreesToCounts(wrapped)));
    writeOne(*profile_.start);
    return 0;
  });
}

void ModbusTurntable::home() {
  if (!profile_.home) unsupported("home");
  withRetry("home", [&] {
    writeOne(*profile_.home);
    return 0;
  });
}

void ModbusTurntable::stop() {
  if (!profile_.stop) unsupported("stop");
  withRetry("stop", [&] {
    writeOne(*profile_.stop);
    return 0;
  });
}

}  // namespace keyturn::drivers
