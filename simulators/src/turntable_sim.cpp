#include "keyturn/sim/turntable_sim.h"

#include <arpa/inet.h>
#include <fcntl.h>
#include <modbus/modbus.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <vector>

#include "keyturn/core/error.h"
#include "keyturn/sim/mesasr_sim_config.h"

namespace keyturn::sim {

namespace {
constexpr double kCountsPerRev = 36000.0;  // the keyturn-sim profile: 0.01° per count
constexpr int kRegPosition = 0, kRegStatus = 2, kRegTarget = 10, kRegCommand = 12, kRegisters = 32;
double wrap360(double a) {
  const double w = std::fmod(a, 360.0);
  return w < 0 ? w + 360.0 : w;
}
}  // namespace

TurntableModel::TurntableModel(TurntableMotion motion, std::uint64_t seed) : m_(motion), rng_(seed) {}

double TurntableModel::trajectory(double t) const {
  // Trapezoidal (or triangular) velocity profile from start_ to goal_.
  const double d = goal_ - start_, dist = std::abs(d), sgn = d < 0 ? -1.0 : 1.0;
  if (dist == 0 || t >= duration_) return goal_;
  const double a = m_.max_accel_deg_s2, v = m_.max_speed_deg_s;
  const double t_acc = std::min(v / a, std::sqrt(dist / a));
  const double v_peak = a * t_acc, d_acc = 0.5 * a * t_acc * t_acc;
  const double t_flat = (dist - 2 * d_acc) / v_peak;
  double s;
  if (t < t_acc) s = 0.5 * a * t * t;
  else if (t < t_acc + t_flat) s = d_acc + v_peak * (t - t_acc);
  else {
    const double td = t - t_acc - t_flat;
    s = d_acc + v_peak * t_flat + v_peak * td - 0.5 * a * td * td;
  }
  return start_ + sgn * std::min(s, dist);
}

void TurntableModel::moveTo(double target_deg, Clock::time_point now) {
  const State cur = state(now);
  const double from = cur.angle_deg - backlash_offset_;
  // Shortest way round.
  double delta = wrap360(target_deg) - wrap360(from);
  if (delta > 180) delta -= 360;
  if (delta < -180) delta += 360;
  if (never_reach_) delta -= (delta >= 0 ? 0.5 : -0.5);
  const int dir = delta > 0 ? 1 : delta < 0 ? -1 : last_dir_;
  // Reversing takes up the gear's lost motion: the table ends short by the backlash.
  backlash_offset_ = (last_dir_ != 0 && dir != last_dir_) ? -dir * m_.backlash_deg : 0.0;
  last_dir_ = dir;
  start_ = from;
  goal_ = from + delta;
  const double dist = std::abs(delta), a = m_.max_accel_deg_s2, v = m_.max_speed_deg_s;
  const double t_acc = std::min(v / a, std::sqrt(dist / a));
  const double d_acc = 0.5 * a * t_acc * t_acc;
  duration_ = dist == 0 ? 0 : 2 * t_acc + (dist - 2 * d_acc) / (a * t_acc);
  t0_ = now;
}

void TurntableModel::stop(Clock::time_point now) {
  const double here = trajectory(std::chrono::duration<double>(now - t0_).count());
  start_ = goal_ = here;
  duration_ = 0;
  t0_ = now;
}

TurntableModel::State TurntableModel::state(Clock::time_point now) {
  const double t = std::chrono::duration<double>(now - t0_).count();
  State s;
  double angle = trajectory(t) + backlash_offset_;
  s.moving = t < duration_;
  const bool settling = !s.moving && t < duration_ + m_.settle_s;
  if (settling) angle += std::uniform_real_distribution<double>(-m_.jitter_deg, m_.jitter_deg)(rng_);
  s.in_position = !s.moving && !settling && !never_reach_;
  s.angle_deg = wrap360(angle);
  return s;
}

TurntableServer::TurntableServer(TurntableServerOptions options)
    : o_(std::move(options)), model_(o_.motion, o_.seed), fault_rng_(o_.seed * 104729 + std::random_device{}()) {
  model_.setNeverReach(o_.faults.never_reach);
  auto* map = modbus_mapping_new(0, 0, kRegisters, 0);
  if (!map) throw Error("simulated turntable: cannot allocate the register map");
  mapping_ = map;
  if (o_.rtu) {
    pty_master_ = ::posix_openpt(O_RDWR | O_NOCTTY);
    if (pty_master_ < 0 || ::grantpt(pty_master_) != 0 || ::unlockpt(pty_master_) != 0)
      throw Error("simulated turntable: cannot create a pseudo-terminal");
    pty_ = ::ptsname(pty_master_);
    modbus_t* ctx = modbus_new_rtu(pty_.c_str(), 115200, 'N', 8, 1);
    modbus_set_slave(ctx, o_.unit_id);
    modbus_set_socket(ctx, pty_master_);  // serve on the master side; clients open pty_
    ctx_ = ctx;
    thread_ = std::thread([this] { serveRtu(); });
  } else {
    modbus_t* ctx = modbus_new_tcp(o_.tcp_address.c_str(), o_.tcp_port);
    if (!ctx) throw Error("simulated turntable: bad address " + o_.tcp_address);
    listen_fd_ = modbus_tcp_listen(ctx, 4);
    if (listen_fd_ < 0) {
      modbus_free(ctx);
      throw Error("simulated turntable: cannot listen on " + o_.tcp_address + ":" + std::to_string(o_.tcp_port) +
                  ": " + modbus_strerror(errno));
    }
    sockaddr_in addr{};
    socklen_t len = sizeof addr;
    ::getsockname(listen_fd_, reinterpret_cast<sockaddr*>(&addr), &len);
    port_ = ntohs(addr.sin_port);
    ctx_ = ctx;
    thread_ = std::thread([this] { serveTcp(); });
  }
}

TurntableServer::~TurntableServer() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
  if (listen_fd_ >= 0) ::close(listen_fd_);
  if (ctx_) {
    if (!o_.rtu) modbus_free(static_cast<modbus_t*>(ctx_));
    else modbus_free(static_cast<modbus_t*>(ctx_));  // pty master closed below
  }
  if (pty_master_ >= 0) ::close(pty_master_);
  modbus_mapping_free(static_cast<modbus_mapping_t*>(mapping_));
}

std::string TurntableServer::endpoint() const {
  if (o_.rtu) return "modbus-rtu:" + pty_ + "@" + std::to_string(o_.unit_id);
  return "modbus-tcp:" + o_.tcp_address + ":" + std::to_string(port_) + "@" + std::to_string(o_.unit_id);
}

void TurntableServer::syncRegisters(TurntableModel::Clock::time_point now) {
  auto* map = static_cast<modbus_mapping_t*>(mapping_);
  const auto s = model_.state(now);
  const auto counts = static_cast<std::uint32_t>(std::llround(s.angle_deg / 360.0 * kCountsPerRev)) %
                      static_cast<std::uint32_t>(kCountsPerRev);
  map->tab_registers[kRegPosition] = static_cast<std::uint16_t>(counts >> 16);
  map->tab_registers[kRegPosition + 1] = static_cast<std::uint16_t>(counts & 0xFFFF);
  map->tab_registers[kRegStatus] = static_cast<std::uint16_t>((s.moving ? 1 : 0) | (s.in_position ? 2 : 0));
  // Every change, however small: a poll 5 µs before arrival read 89.99998°, and with a 1e-4° dead band
  // the arrival at 90° was never written, so the simulated camera drew that view's noise for 89.99998°
  // (issue 51: `simulate --camera openni2` twice gave two different 90° views). Still, nothing changes.
  if (!o_.world_file.empty() && s.angle_deg != last_world_) {
    writeWorldTurntable(o_.world_file, s.angle_deg);
    last_world_ = s.angle_deg;
  }
}

void TurntableServer::applyCommands(TurntableModel::Clock::time_point now) {
  auto* map = static_cast<modbus_mapping_t*>(mapping_);
  const std::uint16_t cmd = map->tab_registers[kRegCommand];
  if (cmd == 0) return;
  const std::uint32_t target = (std::uint32_t(map->tab_registers[kRegTarget]) << 16) | map->tab_registers[kRegTarget + 1];
  if (cmd == 1) model_.moveTo(target / kCountsPerRev * 360.0, now);
  else if (cmd == 2) model_.home(now);
  else if (cmd == 3) model_.stop(now);
  map->tab_registers[kRegCommand] = 0;
}

bool TurntableServer::handle(void* ctxp, const std::uint8_t* query, int length, int) {
  auto* ctx = static_cast<modbus_t*>(ctxp);
  const long n = ++requests_;
  const auto& f = o_.faults;
  if (f.drop_every > 0 && n % f.drop_every == 0) {
    ++faults_;
    return false;
  }
  if (f.no_reply_every > 0 && n % f.no_reply_every == 0) {
    ++faults_;
    return true;
  }
  if (f.random_rate > 0 && std::uniform_real_distribution<double>(0, 1)(fault_rng_) < f.random_rate) {
    ++faults_;
    return fault_rng_() % 2 == 0;  // no reply (keep the connection) or drop it
  }
  if (f.exception_every > 0 && n % f.exception_every == 0) {
    ++faults_;
    modbus_reply_exception(ctx, query, MODBUS_EXCEPTION_SLAVE_OR_SERVER_FAILURE);
    return true;
  }
  // One instant per request, taken when it arrives: a command applied after the reply read the clock
  // whenever this thread got to it, so a client that moved on at once (a test stepping its clock, a
  // loaded machine) saw the move begin late (the hardening CI's 0.002° instead of 90°).
  const auto now = o_.clock ? o_.clock() : TurntableModel::Clock::now();
  syncRegisters(now);
  modbus_reply(ctx, query, length, static_cast<modbus_mapping_t*>(mapping_));
  applyCommands(now);
  syncRegisters(now);
  return true;
}

void TurntableServer::serveTcp() {
  auto* ctx = static_cast<modbus_t*>(ctx_);
  std::vector<pollfd> fds{{listen_fd_, POLLIN, 0}};
  std::uint8_t query[MODBUS_TCP_MAX_ADU_LENGTH];
  while (!stop_) {
    if (::poll(fds.data(), fds.size(), 50) <= 0) continue;
    for (std::size_t i = 0; i < fds.size(); ++i) {
      if (!(fds[i].revents & (POLLIN | POLLHUP | POLLERR))) continue;
      if (fds[i].fd == listen_fd_) {
        const int c = ::accept(listen_fd_, nullptr, nullptr);
        if (c >= 0) fds.push_back({c, POLLIN, 0});
        continue;
      }
      modbus_set_socket(ctx, fds[i].fd);
      const int rc = modbus_receive(ctx, query);
      if (rc > 0 && query[6] != o_.unit_id) {
        // The MBAP header's unit id (byte 6): another unit behind this address does not answer,
        // as a Modbus TCP gateway reports it (libmodbus filters unit ids on RTU only).
        modbus_reply_exception(ctx, query, MODBUS_EXCEPTION_GATEWAY_TARGET);
        continue;
      }
      if (rc > 0 && handle(ctx, query, rc, fds[i].fd)) continue;
      if (rc == 0) continue;  // not for this unit
      ::close(fds[i].fd);
      fds.erase(fds.begin() + static_cast<std::ptrdiff_t>(i));
      --i;
    }
  }
  for (std::size_t i = 1; i < fds.size(); ++i) ::close(fds[i].fd);
}

void TurntableServer::serveRtu() {
  auto* ctx = static_cast<modbus_t*>(ctx_);
  std::uint8_t query[MODBUS_RTU_MAX_ADU_LENGTH];
  pollfd pfd{pty_master_, POLLIN, 0};
  while (!stop_) {
    if (::poll(&pfd, 1, 50) <= 0 || !(pfd.revents & POLLIN)) {
      // A closed client side shows as POLLHUP on the master until reopened.
      if (pfd.revents & POLLHUP) std::this_thread::sleep_for(std::chrono::milliseconds(20));
      continue;
    }
    const int rc = modbus_receive(ctx, query);
    if (rc > 0) handle(ctx, query, rc, pty_master_);
    else if (rc == -1) modbus_flush(ctx);  // a garbled frame: drop it and listen again
  }
}

}  // namespace keyturn::sim
