#pragma once
// The simulated turntable: a motion model (speed and acceleration limits,
// settling with encoder jitter, backlash on reversal) served over Modbus TCP
// (loopback unless told otherwise) or RTU on a pseudo-terminal, with the
// "keyturn-sim" register map (drivers/modbus_profile.h). It writes the angle to
// the shared world file so the simulated camera sees the object turned.
#include <atomic>
#include <chrono>
#include <functional>
#include <cmath>
#include <memory>
#include <mutex>
#include <random>
#include <string>
#include <thread>

namespace keyturn::sim {

struct TurntableMotion {
  double max_speed_deg_s = 60.0;
  double max_accel_deg_s2 = 120.0;
  double settle_s = 0.05;          // jitter after arrival, then still
  double jitter_deg = 0.01;        // ± encoder jitter while settling
  double backlash_deg = 0.05;      // lost motion when the direction reverses
};

struct TurntableFaults {
  int no_reply_every = 0;    // every Nth request gets no reply
  int exception_every = 0;   // every Nth request gets exception 4 (server device failure)
  int drop_every = 0;        // every Nth request closes the connection
  bool never_reach = false;  // moves stop 0.5° short and never report in position
  double random_rate = 0;    // each request: no reply or a dropped connection with this probability
};

class TurntableModel {
 public:
  explicit TurntableModel(TurntableMotion motion = TurntableMotion(), std::uint64_t seed = 1);
  using Clock = std::chrono::steady_clock;
  void moveTo(double target_deg, Clock::time_point now);
  void home(Clock::time_point now) { moveTo(0.0, now); }
  void stop(Clock::time_point now);
  struct State {
    double angle_deg;  // what the encoder reads, [0, 360)
    bool moving;
    bool in_position;
  };
  State state(Clock::time_point now);
  void setNeverReach(bool v) { never_reach_ = v; }

 private:
  double trajectory(double t) const;  // unwrapped angle along the current move
  TurntableMotion m_;
  double start_ = 0, goal_ = 0, duration_ = 0;
  Clock::time_point t0_{};
  int last_dir_ = 0;
  double backlash_offset_ = 0;
  bool never_reach_ = false;
  std::mt19937_64 rng_;
};

struct TurntableServerOptions {
  std::string tcp_address = "127.0.0.1";
  int tcp_port = 0;          // 0: choose a free port
  bool rtu = false;          // serve RTU on a pseudo-terminal instead of TCP
  int unit_id = 1;
  std::string world_file;    // shared world state written on every change
  TurntableMotion motion;
  TurntableFaults faults;
  std::uint64_t seed = 1;
  // The motion's clock; empty: the steady clock. A test gives one it advances, so what a read
  // reports during a move depends on the time it set, not on how fast the machine answers.
  std::function<std::chrono::steady_clock::time_point()> clock;
};

class TurntableServer {
 public:
  explicit TurntableServer(TurntableServerOptions options);  // starts serving; throws keyturn::Error
  ~TurntableServer();
  int port() const { return port_; }                  // TCP
  const std::string& ptyPath() const { return pty_; }  // RTU: the device a client opens
  std::string endpoint() const;                       // "modbus-tcp:127.0.0.1:PORT" / "modbus-rtu:/dev/pts/N"
  long requests() const { return requests_; }
  long faultsInjected() const { return faults_; }

 private:
  void serveTcp();
  void serveRtu();
  bool handle(void* ctx, const std::uint8_t* query, int length, int socket);  // false: drop connection
  void syncRegisters(TurntableModel::Clock::time_point now);
  void applyCommands(TurntableModel::Clock::time_point now);

  TurntableServerOptions o_;
  TurntableModel model_;
  void* mapping_ = nullptr;
  int listen_fd_ = -1, pty_master_ = -1, port_ = 0;
  std::string pty_;
  std::atomic<bool> stop_{false};
  std::atomic<long> requests_{0}, faults_{0};
  double last_world_ = std::nan("");  // none written yet: the first request writes the angle
  std::mt19937_64 fault_rng_;
  std::thread thread_;
  void* ctx_ = nullptr;
};

}  // namespace keyturn::sim
