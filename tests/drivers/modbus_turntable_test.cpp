// The Modbus turntable driver against the simulated turntable over real
// libmodbus TCP on loopback and RTU on a pseudo-terminal.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <thread>

#include "keyturn/core/error.h"
#include "support/error_of.h"
#include "keyturn/drivers/modbus_turntable.h"
#include "keyturn/sim/mesasr_sim_config.h"
#include "keyturn/sim/turntable_sim.h"
#include "support/scratch_path.h"

using namespace keyturn;
using keyturn::test::errorOf;
using namespace keyturn::drivers;
using Clock = std::chrono::steady_clock;

namespace {

sim::TurntableServerOptions fastTable() {
  sim::TurntableServerOptions o;
  o.motion.max_speed_deg_s = 360;
  o.motion.max_accel_deg_s2 = 3600;
  o.motion.settle_s = 0.02;
  return o;
}

std::unique_ptr<ModbusTurntable> connectTo(const sim::TurntableServer& s, std::vector<std::string>* log = nullptr) {
  ModbusOptions o;
  o.timeout_ms = 100;
  o.backoff_initial_ms = 5;
  if (log) o.log = [log](const std::string& l) { log->push_back(l); };
  return std::make_unique<ModbusTurntable>(ModbusEndpoint::parse(s.endpoint()),
                                           ModbusTurntableProfile::load("keyturn-sim"), o);
}

Pose waitInPosition(ModbusTurntable& t, double timeout_s = 3.0) {
  const auto end = Clock::now() + std::chrono::duration<double>(timeout_s);
  Pose p = t.read();
  while (!p.in_position && Clock::now() < end) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    p = t.read();
  }
  return p;
}


}  // namespace

TEST(ModbusProfile, BuiltInsAndTheirConversions) {
  const auto enc = ModbusTurntableProfile::load("generic-encoder");
  EXPECT_EQ(enc.position.address, 0);
  EXPECT_EQ(enc.position.bits, 32);
  EXPECT_FALSE(enc.motorised());
  EXPECT_NEAR(enc.countsToDegrees(1024), 90.0, 1e-9);
  EXPECT_NEAR(enc.countsToDegrees(4096 * 3 + 2048), 180.0, 1e-9);  // multi-turn count wraps
  const auto simp = ModbusTurntableProfile::load("keyturn-sim");
  EXPECT_TRUE(simp.motorised());
  EXPECT_NEAR(simp.degreesToCounts(12.5), 1250.0, 1e-9);
}

TEST(ModbusProfile, BadFilesAreNamed) {
  EXPECT_EQ(errorOf([] { ModbusTurntableProfile::fromJson("{", "p.json"); }),
            "p.json: not JSON at byte 1 (unexpected end of input; expected string literal)");
  EXPECT_EQ(errorOf([] { ModbusTurntableProfile::fromJson("[]", "p.json"); }), "p.json: expected a JSON object, found an array");
  EXPECT_NE(errorOf([] {
              ModbusTurntableProfile::fromJson(R"({"position":{"address":0,"bits":24},"counts_per_revolution":1})", "p.json");
            }).find("p.json: position: bits must be 16 or 32"),
            std::string::npos);
  EXPECT_NE(errorOf([] {
              ModbusTurntableProfile::fromJson(R"({"position":{"address":0},"counts_per_revolution":1,"direction":2})", "p.json");
            }).find("direction must be 1 or -1"),
            std::string::npos);
  EXPECT_NE(errorOf([] { ModbusTurntableProfile::load("/nonexistent.json"); }).find("no such Modbus profile"),
            std::string::npos);
}

TEST(ModbusProfile, NumbersThatDoNotFitAnIntegerAreNamedNotCast) {
  // nlohmann's get<int>() would cast 1e30 (undefined behaviour) and wrap 4294967296 to 0.
  auto err = [](const std::string& json) { return errorOf([&] { ModbusTurntableProfile::fromJson(json, "p.json"); }); };
  EXPECT_EQ(err(R"({"position":{"address":1e30},"counts_per_revolution":1})"),
            "p.json: position: address must be an integer in 0..65535, not 1e+30");
  EXPECT_EQ(err(R"({"position":{"address":4294967296},"counts_per_revolution":1})"),
            "p.json: position: address must be an integer in 0..65535, not 4294967296");
  EXPECT_EQ(err(R"({"position":{"address":2.5},"counts_per_revolution":1})"),
            "p.json: position: address must be an integer in 0..65535, not 2.5");
  EXPECT_EQ(err(R"({"position":{"address":65535,"bits":32},"counts_per_revolution":1})"),
            "p.json: position: address must be an integer in 0..65534, not 65535");
  EXPECT_EQ(err(R"({"position":{"address":0},"counts_per_revolution":1,"direction":-1e300})"),
            "p.json: direction must be an integer in -2147483648..2147483647, not -1e+300");
  // A status bit past 15 would shift a 16-bit register out of range; a write value must fit 16 bits.
  EXPECT_EQ(err(R"({"position":{"address":0},"counts_per_revolution":1,"commands":{"status":{"address":2,"moving_bit":99}}})"),
            "p.json: commands.status: moving_bit must be an integer in 0..15, not 99");
  EXPECT_EQ(err(R"({"position":{"address":0},"counts_per_revolution":1,"commands":{"start":{"address":12,"value":-1}}})"),
            "p.json: commands.start: value must be an integer in 0..65535, not -1");
  // A target in counts must fit the 32-bit register (llround of 1e300 has no value).
  EXPECT_EQ(err(R"({"position":{"address":0},"counts_per_revolution":1e300})"),
            "p.json: counts_per_revolution must be in (0, 2^32]");
  EXPECT_EQ(err(R"({"position":{"address":0},"counts_per_revolution":1,"zero_offset_deg":1e300})"),
            "p.json: zero_offset_deg must be in -360..360");
  const auto ok = ModbusTurntableProfile::fromJson(
      R"({"position":{"address":65534,"bits":32},"counts_per_revolution":4294967296,"commands":{"status":{"address":3,"moving_bit":15}}})",
      "p.json");
  EXPECT_EQ(ok.position.address, 65534);
  EXPECT_EQ(ok.status->moving_bit, 15);
  EXPECT_EQ(ok.status->in_position_bit, 1);
}

TEST(ModbusEndpoint, ParsesTcpAndRtu) {
  const auto t = ModbusEndpoint::parse("modbus-tcp:10.0.0.5:1502@7");
  EXPECT_EQ(t.host, "10.0.0.5");
  EXPECT_EQ(t.port, 1502);
  EXPECT_EQ(t.unit_id, 7);
  const auto r = ModbusEndpoint::parse("modbus-rtu:/dev/ttyUSB0:19200:8E1@3");
  EXPECT_EQ(r.device, "/dev/ttyUSB0");
  EXPECT_EQ(r.baud, 19200);
  EXPECT_EQ(r.parity, 'E');
  EXPECT_EQ(r.unit_id, 3);
  EXPECT_THROW(ModbusEndpoint::parse("modbus-tcp:host"), Error);
  // Whole numbers in range, not atoi's wrap: unit 4294967297 is not unit 1, port 65536+502 not 502.
  EXPECT_EQ(errorOf([] { ModbusEndpoint::parse("modbus-tcp:h:502@4294967297"); }),
            "pose source 'modbus-tcp:h:502@4294967297': unit id must be 1..247");
  EXPECT_EQ(errorOf([] { ModbusEndpoint::parse("modbus-tcp:h:66038"); }), "pose source 'modbus-tcp:h:66038': bad host or port");
  EXPECT_EQ(errorOf([] { ModbusEndpoint::parse("modbus-rtu:/dev/ttyS0:9600x"); }),
            "pose source 'modbus-rtu:/dev/ttyS0:9600x': bad baud rate");
  EXPECT_THROW(ModbusEndpoint::parse("can:can0"), Error);
}

// The move on the simulator's clock, set by the test: each read reports the instant the test chose,
// however late the machine answers (a read right after moveTo on the steady clock could come after the
// whole 0.37 s move on a loaded machine).
TEST(ModbusTurntable, MovesOverTcpWithARealisticProfile) {
  const auto start = std::chrono::steady_clock::now();
  std::atomic<long> at_us{0};
  sim::TurntableServerOptions o = fastTable();
  o.clock = [&] { return start + std::chrono::microseconds(at_us.load()); };
  sim::TurntableServer server(o);
  auto table = connectTo(server);
  EXPECT_NEAR(table->read().turntable_deg, 0.0, 1e-9);
  table->moveTo(90.0);
  // 360°/s, 3600°/s²: 0.1 s ramps (18° each) and 0.15 s at full speed, arriving at 0.35 s; then 0.02 s
  // of settling jitter (±0.01°).
  const Pose begun = table->read();
  EXPECT_TRUE(begun.moving);
  EXPECT_FALSE(begun.in_position);
  EXPECT_NEAR(begun.turntable_deg, 0.0, 1e-9);
  const auto readAt = [&](double s) {
    at_us = std::lround(s * 1e6);
    return table->read();
  };
  const Pose ramp = readAt(0.05);  // half the ramp: 0.5 · 3600 · 0.05² = 4.5°
  EXPECT_TRUE(ramp.moving);
  EXPECT_NEAR(ramp.turntable_deg, 4.5, 0.01);
  const Pose cruise = readAt(0.2);  // 18° + 360 · 0.1 = 54°
  EXPECT_TRUE(cruise.moving);
  EXPECT_NEAR(cruise.turntable_deg, 54.0, 0.01);
  const Pose settling = readAt(0.36);
  EXPECT_FALSE(settling.moving);
  EXPECT_FALSE(settling.in_position);
  EXPECT_NEAR(settling.turntable_deg, 90.0, 0.011);
  const Pose end = readAt(0.38);
  EXPECT_TRUE(end.in_position);
  EXPECT_NEAR(end.turntable_deg, 90.0, 0.011);
}

// The shared world (what the simulated cameras render) ends exactly where the table stops, however
// close to the goal the last read during the move was: 100 µs before arrival the table is 1.8e-5° short
// (0.5 · 3600°/s² · (1e-4 s)²), inside the 1e-4° dead band the world file once had, and 90° was then
// never written.
TEST(ModbusTurntable, TheWorldEndsExactlyWhereTheTableStops) {
  const test::ScratchFolder scratch("turntable_world");
  const std::string world = (scratch.made() / "world.json").string();
  const auto start = std::chrono::steady_clock::now();
  std::atomic<long> at_us{0};
  sim::TurntableServerOptions o = fastTable();
  o.motion.settle_s = 0;
  o.world_file = world;
  o.clock = [&] { return start + std::chrono::microseconds(at_us.load()); };
  sim::TurntableServer server(o);
  auto table = connectTo(server);
  table->read();
  EXPECT_EQ(sim::readWorldTurntable(world, -1.0), 0.0);  // written at the first request
  table->moveTo(90.0);
  at_us = 350000 - 100;  // arrival at 0.35 s (see MovesOverTcpWithARealisticProfile)
  EXPECT_TRUE(table->read().moving);
  const double last_moving = sim::readWorldTurntable(world, -1.0);
  EXPECT_GT(last_moving, 90.0 - 1e-4);
  EXPECT_LT(last_moving, 90.0);
  at_us = 351000;
  EXPECT_FALSE(table->read().moving);
  EXPECT_EQ(sim::readWorldTurntable(world, -1.0), 90.0);
}

// A command takes effect at the instant its request arrives. The simulator once read its clock for a
// command after sending the reply, whenever its thread got there: the hardening CI's run of the test
// above stepped the clock to 100 µs before arrival first, so the move began then (0° "moving", then
// 0.002178° = ½ · 3600°/s² · (1.1 ms)² where 90° was due). Here the clock holds every read until the
// test has stepped it (or 300 ms): a read after the reply sees 0.2 s, one on arrival 0.
TEST(ModbusTurntable, AMoveBeginsWhenItsRequestArrives) {
  const auto start = std::chrono::steady_clock::now();
  std::atomic<long> at_us{0};
  std::atomic<bool> held{false}, stepped{false};
  sim::TurntableServerOptions o = fastTable();
  o.clock = [&] {
    const auto limit = Clock::now() + std::chrono::milliseconds(300);
    while (held && !stepped && Clock::now() < limit) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    return start + std::chrono::microseconds(at_us.load());
  };
  sim::TurntableServer server(o);
  ModbusOptions patient;
  patient.timeout_ms = 2000;  // a held read must not time the request out
  ModbusTurntable table(ModbusEndpoint::parse(server.endpoint()), ModbusTurntableProfile::load("keyturn-sim"), patient);
  table.read();
  held = true;
  table.moveTo(90.0);
  at_us = 200000;
  stepped = true;
  EXPECT_NEAR(table.read().turntable_deg, 54.0, 0.01);  // 0.2 s into the move (the profile above)
}

TEST(ModbusTurntable, InPositionIsNeverPairedWithAStaleAngle) {
  // Position and status come from one request, so a table arriving between two reads cannot report
  // "in position" at an angle it had already left. Polled as tightly as a capture does, over many moves.
  sim::TurntableServer server(fastTable());
  auto table = connectTo(server);
  const long before = server.requests();
  table->read();
  EXPECT_EQ(server.requests() - before, 1);  // one snapshot per read
  int in_position_reads = 0;
  for (int i = 1; i <= 12; ++i) {
    const double target = i * 7.5;
    table->moveTo(target);
    const auto end = Clock::now() + std::chrono::seconds(3);
    for (Pose p = table->read(); Clock::now() < end; p = table->read()) {
      if (!p.in_position) continue;
      ++in_position_reads;
      ASSERT_NEAR(p.turntable_deg, target, 0.011) << "move " << i;
      break;
    }
  }
  EXPECT_EQ(in_position_reads, 12);
}

TEST(ModbusTurntable, ReversingShowsBacklash) {
  sim::TurntableServer server(fastTable());
  auto table = connectTo(server);
  table->moveTo(30.0);
  waitInPosition(*table);
  table->moveTo(10.0);
  EXPECT_NEAR(waitInPosition(*table).turntable_deg, 10.05, 0.011);  // short by the 0.05° backlash
}

TEST(ModbusTurntable, MovesOverRtuOnAPseudoTerminal) {
  auto o = fastTable();
  o.rtu = true;
  o.unit_id = 5;
  sim::TurntableServer server(o);
  ASSERT_EQ(server.ptyPath().rfind("/dev/pts/", 0), 0u);
  auto table = connectTo(server);
  table->moveTo(200.0);
  EXPECT_NEAR(waitInPosition(*table).turntable_deg, 200.0, 0.011);
  EXPECT_GT(server.requests(), 3);
}

TEST(ModbusTurntable, LostRepliesAreRetried) {
  auto o = fastTable();
  o.faults.no_reply_every = 3;
  sim::TurntableServer server(o);
  std::vector<std::string> log;
  auto table = connectTo(server, &log);
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(table->read().turntable_deg, 0.0, 1e-9);
  EXPECT_GT(server.faultsInjected(), 0);
  ASSERT_FALSE(log.empty());
  EXPECT_NE(log[0].find("read: reading register 0: no reply (timed out); retrying in 5 ms (attempt 1 of 3)"), std::string::npos) << log[0];
}

TEST(ModbusTurntable, DroppedConnectionsAreReconnected) {
  auto o = fastTable();
  o.faults.drop_every = 3;  // a read is two requests (position, status)
  sim::TurntableServer server(o);
  auto table = connectTo(server);
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(table->read().turntable_deg, 0.0, 1e-9);
  EXPECT_GE(table->reconnects(), 2);
}

TEST(ModbusTurntable, ModbusExceptionsAreNamedAndNotRetried) {
  auto o = fastTable();
  o.faults.exception_every = 1;
  sim::TurntableServer server(o);
  std::vector<std::string> log;
  auto table = connectTo(server, &log);
  const std::string msg = errorOf([&] { table->read(); });
  EXPECT_NE(msg.find("reading register 0: Modbus exception 4 (Slave device or server failure)"), std::string::npos)
      << msg;
  EXPECT_TRUE(log.empty());
  EXPECT_EQ(server.requests(), 1);
}

TEST(ModbusTurntable, TheSimulatedTcpTableAnswersOnlyItsUnitId) {
  auto o = fastTable();
  o.unit_id = 3;
  sim::TurntableServer server(o);
  std::string other = server.endpoint();
  other.replace(other.rfind('@'), std::string::npos, "@4");
  ModbusOptions mo;
  mo.timeout_ms = 100;
  ModbusTurntable wrong(ModbusEndpoint::parse(other), ModbusTurntableProfile::load("keyturn-sim"), mo);
  const std::string msg = errorOf([&] { wrong.read(); });
  EXPECT_NE(msg.find("unit 4"), std::string::npos) << msg;
  EXPECT_NE(msg.find("Modbus exception 11"), std::string::npos) << msg;
  EXPECT_EQ(server.requests(), 0);
  EXPECT_NEAR(connectTo(server)->read().turntable_deg, 0.0, 1e-9);  // its own unit id still answers
}

TEST(ModbusTurntable, ATableThatNeverArrivesIsVisible) {
  auto o = fastTable();
  o.faults.never_reach = true;
  sim::TurntableServer server(o);
  auto table = connectTo(server);
  table->moveTo(40.0);
  const Pose p = waitInPosition(*table, 0.6);
  EXPECT_FALSE(p.in_position);
  EXPECT_FALSE(p.moving);
  EXPECT_NEAR(p.turntable_deg, 39.5, 0.011);
}

TEST(ModbusTurntable, NoServerIsAClearError) {
  ModbusOptions o;
  o.timeout_ms = 100;
  const std::string msg = errorOf([&] {
    ModbusTurntable t(ModbusEndpoint::parse("modbus-tcp:127.0.0.1:1"), ModbusTurntableProfile::load("keyturn-sim"), o);
  });
  EXPECT_NE(msg.find("modbus-tcp 127.0.0.1:1 unit 1 (keyturn-sim): cannot connect: Connection refused"),
            std::string::npos)
      << msg;
}

TEST(ModbusTurntable, ReadOnlyEncoderRefusesToMove) {
  sim::TurntableServer server(fastTable());
  ModbusOptions o;
  ModbusTurntable enc(ModbusEndpoint::parse(server.endpoint()), ModbusTurntableProfile::load("generic-encoder"), o);
  EXPECT_NE(errorOf([&] { enc.moveTo(10); }).find("cannot move (a read-only pose source)"), std::string::npos);
}

TEST(ModbusTurntable, TheSimulatedTableWritesTheSharedWorld) {
  const keyturn::test::ScratchFolder scratch("modbus_world");  // removed after the server below stops
  auto o = fastTable();
  o.world_file = (scratch.made() / "world.json").string();
  sim::TurntableServer server(o);
  auto table = connectTo(server);
  table->moveTo(135.0);
  const Pose p = waitInPosition(*table);
  EXPECT_NEAR(sim::readWorldTurntable(o.world_file, -1), p.turntable_deg, 0.011);
}

namespace {
// A loopback "device" that answers every request with the given bytes.
class GarbagePeer {
 public:
  explicit GarbagePeer(std::vector<std::uint8_t> reply) : reply_(std::move(reply)) {
    fd_ = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    ::bind(fd_, reinterpret_cast<sockaddr*>(&a), sizeof a);
    ::listen(fd_, 1);
    socklen_t len = sizeof a;
    ::getsockname(fd_, reinterpret_cast<sockaddr*>(&a), &len);
    port_ = ntohs(a.sin_port);
    thread_ = std::thread([this] {
      const int c = ::accept(fd_, nullptr, nullptr);
      std::uint8_t buf[512];
      while (c >= 0 && ::recv(c, buf, sizeof buf, 0) > 0)
        if (::send(c, reply_.data(), reply_.size(), MSG_NOSIGNAL) < 0) break;
      if (c >= 0) ::close(c);
    });
  }
  ~GarbagePeer() {
    ::shutdown(fd_, SHUT_RDWR);
    ::close(fd_);
    thread_.detach();  // it ends when the client disconnects
  }
  std::string endpoint() const { return "modbus-tcp:127.0.0.1:" + std::to_string(port_); }

 private:
  std::vector<std::uint8_t> reply_;
  int fd_ = -1, port_ = 0;
  std::thread thread_;
};

std::string readFrom(const GarbagePeer& peer) {
  ModbusOptions o;
  o.timeout_ms = 100;
  o.retries = 1;
  o.backoff_initial_ms = 1;
  return errorOf([&] {
    ModbusTurntable t(ModbusEndpoint::parse(peer.endpoint()), ModbusTurntableProfile::load("keyturn-sim"), o);
    t.read();
  });
}
}  // namespace

TEST(ModbusTurntable, APeerSendingGarbageIsAClearError) {
  std::vector<std::uint8_t> junk(300);
  for (std::size_t i = 0; i < junk.size(); ++i) junk[i] = static_cast<std::uint8_t>(i * 37 + 11);
  GarbagePeer peer(junk);
  const std::string msg = readFrom(peer);
  EXPECT_NE(msg.find("modbus-tcp 127.0.0.1:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("read failed after 1 retries: reading register 0:"), std::string::npos) << msg;
}

TEST(ModbusTurntable, APeerAnnouncingAnOversizeFrameIsAClearError) {
  // MBAP header claiming 65535 bytes follow, then a few.
  GarbagePeer peer({0x00, 0x01, 0x00, 0x00, 0xFF, 0xFF, 0x01, 0x03, 0xFA, 0x00, 0x01});
  const std::string msg = readFrom(peer);
  EXPECT_NE(msg.find("reading register 0:"), std::string::npos) << msg;
}
