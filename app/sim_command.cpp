// keyturn sim turntable: serve the simulated turntable over Modbus TCP
// (loopback unless an address is given) or RTU on a pseudo-terminal until
// interrupted. The first line on standard output names the endpoint.
#include <atomic>
#include <csignal>
#include <cstdio>
#include <iostream>
#include <thread>

#include "commands.h"
#include "keyturn/core/error.h"
#include "keyturn/sim/turntable_sim.h"

namespace keyturn::app {
namespace {

std::atomic<bool> g_stop{false};
void onSignal(int) { g_stop = true; }

struct SimArgs {
  std::string tcp = "127.0.0.1:1502";
  sim::TurntableServerOptions o;  // bound to the options (motion, faults, unit, world)
  double duration = 0;
};

int runSimTurntable(SimArgs a) {
  sim::TurntableServerOptions& o = a.o;
  if (!o.rtu) {
    const auto colon = a.tcp.rfind(':');
    if (colon == std::string::npos) throw Error("--modbus-tcp: expected ADDRESS:PORT, got '" + a.tcp + "'");
    o.tcp_address = a.tcp.substr(0, colon);
    o.tcp_port = std::atoi(a.tcp.c_str() + colon + 1);
  }
  sim::TurntableServer server(o);
  std::signal(SIGINT, onSignal);
  std::signal(SIGTERM, onSignal);
  std::cout << server.endpoint() << std::endl;
  std::cerr << "keyturn sim turntable: serving the keyturn-sim profile on " << server.endpoint()
            << " (Ctrl-C to stop)\n";
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(a.duration);
  while (!g_stop && (a.duration <= 0 || std::chrono::steady_clock::now() < end))
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  std::cerr << "keyturn sim turntable: " << server.requests() << " requests, " << server.faultsInjected()
            << " faults injected\n";
  return 0;
}

}  // namespace

Command addSimCommand(CLI::App& app) {
  auto a = std::make_shared<SimArgs>();
  auto* sim = app.add_subcommand("sim", "Simulated devices (they speak the real devices' protocols)");
  sim->require_subcommand(1);
  auto* tt = sim->add_subcommand("turntable", "Serve the simulated turntable over Modbus TCP or RTU");
  tt->add_option("--modbus-tcp", a->tcp, "ADDRESS:PORT to listen on (loopback unless told otherwise)")
      ->capture_default_str();
  tt->add_flag("--modbus-rtu", a->o.rtu, "Serve RTU on a new pseudo-terminal instead (its path is printed)");
  tt->add_option("--unit", a->o.unit_id, "Modbus unit id")->capture_default_str()->check(CLI::Range(1, 247));
  tt->add_option("--world", a->o.world_file, "Shared world file the simulated camera reads the angle from");
  tt->add_option("--speed", a->o.motion.max_speed_deg_s, "Maximum speed (°/s)")->capture_default_str();
  tt->add_option("--accel", a->o.motion.max_accel_deg_s2, "Maximum acceleration (°/s²)")->capture_default_str();
  tt->add_option("--settle", a->o.motion.settle_s, "Settling time with encoder jitter after arrival (s)")->capture_default_str();
  tt->add_option("--backlash", a->o.motion.backlash_deg, "Lost motion on reversal (°)")->capture_default_str();
  tt->add_option("--no-reply-every", a->o.faults.no_reply_every, "Fault: ignore every Nth request");
  tt->add_option("--exception-every", a->o.faults.exception_every, "Fault: answer every Nth request with exception 4");
  tt->add_option("--drop-every", a->o.faults.drop_every, "Fault: close the connection on every Nth request");
  tt->add_flag("--never-reach", a->o.faults.never_reach, "Fault: stop 0.5° short and never report in position");
  tt->add_option("--duration", a->duration, "Stop after this many seconds (0 = until interrupted)");
  return {sim, [a] { return runSimTurntable(*a); }};
}

}  // namespace keyturn::app
