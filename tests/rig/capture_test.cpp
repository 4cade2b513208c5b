// Capture sequences end to end: the real SR4000 driver on libmesasr-sim and the
// real Modbus driver on the simulated turntable over loopback TCP, one world.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "keyturn/core/error.h"
#include "keyturn/drivers/modbus_turntable.h"
#include "keyturn/drivers/sr4000_camera.h"
#include "keyturn/rig/captured_views.h"
#include "keyturn/rig/capture.h"
#include "keyturn/rig/frame_files.h"
#include "keyturn/dataset/dataset.h"
#include "keyturn/sim/mesasr_sim_config.h"
#include "keyturn/sim/turntable_sim.h"
#include "support/scratch_path.h"

namespace fs = std::filesystem;
using namespace keyturn;

namespace {

class SimulatedRig : public ::testing::Test {
 protected:
  void SetUp() override { world_ = (dir_ / "world.json").string(); }
  void TearDown() override { ::unsetenv("MESASR_SIM_CONFIG"); }

  void start(sim::TurntableFaults faults = {}, sim::MesaSrSimFaults camera_faults = {}) {
    sim::TurntableServerOptions so;
    so.world_file = world_;
    so.motion.max_speed_deg_s = 720;
    so.motion.max_accel_deg_s2 = 14400;
    so.motion.settle_s = 0.005;
    so.faults = faults;
    server_ = std::make_unique<sim::TurntableServer>(so);
    drivers::ModbusOptions mo;
    mo.timeout_ms = 100;
    mo.backoff_initial_ms = 2;
    table_ = std::make_unique<drivers::ModbusTurntable>(drivers::ModbusEndpoint::parse(server_->endpoint()),
                                                        drivers::ModbusTurntableProfile::load("keyturn-sim"), mo);
    sim::MesaSrSimConfig c;
    c.world = world_;
    c.faults = camera_faults;
    const std::string cfg = (dir_ / "camera.json").string();
    c.save(cfg);
    ::setenv("MESASR_SIM_CONFIG", cfg.c_str(), 1);
    drivers::Sr4000Options co;
    co.backoff_initial_ms = 1;
    camera_ = std::make_unique<drivers::Sr4000Camera>(drivers::MesaSrLibrary::load(KEYTURN_MESASR_SIM_PATH),
                                                      drivers::Sr4000Connection::parse("usb"), co);
  }

  rig::CaptureOptions options() const {
    rig::CaptureOptions o;
    o.cls = "mug";
    o.instance = "builtin";
    o.elevation_label = "30";
    o.step_deg = 10;
    o.range_deg = 40;
    o.settle_s = 0.01;
    return o;
  }

  // First: removed after the simulators below, which write into it, have stopped.
  const test::ScratchFolder scratch_{"rig"};
  const fs::path& dir_ = scratch_.made();
  std::string world_;
  std::unique_ptr<sim::TurntableServer> server_;
  std::unique_ptr<drivers::ModbusTurntable> table_;
  std::unique_ptr<drivers::Sr4000Camera> camera_;
};

}  // namespace

TEST_F(SimulatedRig, CapturesPoseTaggedViewsThatVerify) {
  start();
  dataset::Dataset ds((dir_ / "ds").string());
  auto o = options();
  o.camera_from_turntable_zero = Eigen::Matrix4d::Identity();
  std::vector<std::string> shown;  // what a GUI would show as thumbnails, in order
  const auto rep = rig::runCapture(*camera_, *table_, ds, o, [&](const rig::CaptureProgress& p) {
    ASSERT_NE(p.frame, nullptr);
    ASSERT_NE(p.record, nullptr);
    EXPECT_EQ(p.frame->width * p.frame->height, p.frame->distance.size());
    EXPECT_DOUBLE_EQ(p.record->key.commanded_deg, p.angle_deg);
    shown.push_back(p.record->files.at(0));
  });
  EXPECT_EQ(rep.written, 4u);
  EXPECT_EQ(shown, (std::vector<std::string>{"mug/builtin/e30/a0.0.pcd", "mug/builtin/e30/a10.0.pcd",
                                             "mug/builtin/e30/a20.0.pcd", "mug/builtin/e30/a30.0.pcd"}));
  const auto views = dataset::Dataset::readManifest(ds.root());
  ASSERT_EQ(views.size(), 4u);
  for (std::size_t i = 0; i < views.size(); ++i) {
    EXPECT_DOUBLE_EQ(views[i].key.commanded_deg, 10.0 * i);
    EXPECT_NEAR(views[i].measured_deg, 10.0 * i, 1e-9);  // read in position: no settling jitter
    EXPECT_EQ(views[i].files.size(), 5u);  // pcd, 3 pngs, json
  }
  std::ifstream in(ds.root() + "/mug/builtin/e30/a20.0.json");
  const auto j = nlohmann::json::parse(in);
  EXPECT_EQ(j["class"], "mug");
  EXPECT_EQ(j["camera"]["serial"], 4000123);
  EXPECT_NEAR(j["camera_from_turntable"][0][0].get<double>(), std::cos(20 * M_PI / 180), 2e-3);
  EXPECT_TRUE(dataset::Dataset::verify(ds.root()).ok());
}

TEST_F(SimulatedRig, AStoppedCaptureResumesWithoutDuplicates) {
  start();
  std::atomic<bool> stop{false};
  {
    dataset::Dataset ds((dir_ / "ds").string());
    auto o = options();
    o.stop = &stop;
    const auto rep = rig::runCapture(*camera_, *table_, ds, o, [&](const rig::CaptureProgress& p) {
      if (p.done == 2) stop = true;
    });
    EXPECT_TRUE(rep.stopped);
    EXPECT_EQ(rep.written, 2u);
  }
  dataset::Dataset again((dir_ / "ds").string());
  const auto rep = rig::runCapture(*camera_, *table_, again, options());
  EXPECT_EQ(rep.skipped, 2u);
  EXPECT_EQ(rep.written, 2u);
  EXPECT_EQ(dataset::Dataset::readManifest(again.root()).size(), 4u);
  EXPECT_TRUE(dataset::Dataset::verify(again.root()).ok());
}

TEST_F(SimulatedRig, TurntableFaultsAreRetriedDuringCapture) {
  sim::TurntableFaults f;
  f.no_reply_every = 7;
  f.drop_every = 11;
  start(f);
  dataset::Dataset ds((dir_ / "ds").string());
  const auto rep = rig::runCapture(*camera_, *table_, ds, options());
  EXPECT_EQ(rep.written, 4u);
  EXPECT_GT(server_->faultsInjected(), 2);
  EXPECT_TRUE(dataset::Dataset::verify(ds.root()).ok());
}

TEST_F(SimulatedRig, CameraTimeoutsAndDisconnectsAreRecoveredDuringCapture) {
  sim::MesaSrSimFaults cf;
  cf.timeout_every = 3;
  cf.disconnect_after = 5;
  start({}, cf);
  dataset::Dataset ds((dir_ / "ds").string());
  auto o = options();
  o.discard_frames = 1;
  const auto rep = rig::runCapture(*camera_, *table_, ds, o);
  EXPECT_EQ(rep.written, 4u);
  EXPECT_GE(camera_->reconnects(), 2);
  EXPECT_TRUE(dataset::Dataset::verify(ds.root()).ok());
}

TEST_F(SimulatedRig, ACameraThatKeepsFailingStopsTheCaptureWithNothingHalfWritten) {
  sim::MesaSrSimFaults cf;
  cf.corrupt_every = 1;
  start({}, cf);
  dataset::Dataset ds((dir_ / "ds").string());
  EXPECT_THROW(rig::runCapture(*camera_, *table_, ds, options()), Error);
  const auto v = dataset::Dataset::verify(ds.root());
  EXPECT_EQ(v.views, 0u);
  EXPECT_TRUE(v.ok());  // no orphan files either
}

TEST_F(SimulatedRig, ATableThatNeverSettlesIsAClearError) {
  sim::TurntableFaults f;
  f.never_reach = true;
  start(f);
  dataset::Dataset ds((dir_ / "ds").string());
  auto o = options();
  o.move_timeout_s = 0.5;
  try {
    rig::runCapture(*camera_, *table_, ds, o);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("not stable within 0.100000° of 0.000000°"), std::string::npos) << e.what();
  }
  // Even 0° is missed by 0.5°: no view was written, and nothing was left behind.
  EXPECT_TRUE(dataset::Dataset::readManifest(ds.root()).empty());
  EXPECT_TRUE(dataset::Dataset::verify(ds.root()).orphans.empty());
}

namespace {

// A 4 × 2 frame of the same 1 m distance everywhere.
drivers::TofFrame tinyFrame() {
  drivers::TofFrame f;
  f.width = 4;
  f.height = 2;
  f.distance.assign(8, 1000);
  f.amplitude.assign(8, 500);
  f.confidence.assign(8, 65535);
  f.cloud.width = 4;
  f.cloud.height = 2;
  f.cloud.points.assign(8, Eigen::Vector3f(0.f, 0.f, 1.f));
  f.cloud.amplitude.assign(8, 500.f);
  return f;
}

}  // namespace

namespace {

// A drive as a Modbus turntable reports one: after a move it is still (not moving) but settling for
// a few reads, the encoder 0.01° off, before it raises "in position" on the exact angle.
class SettlingTable final : public drivers::PoseSource {
 public:
  drivers::Pose read() override {
    drivers::Pose p;
    const bool settling = reads_since_move_++ < 3;
    p.turntable_deg = target_ + (settling ? 0.01 : 0.0);
    p.moving = false;
    p.in_position = !settling;
    return p;
  }
  bool canMove() const override { return true; }
  void moveTo(double deg) override {
    target_ = deg;
    reads_since_move_ = 0;
  }
  std::string describe() const override { return "settling table"; }

 private:
  double target_ = 0;
  int reads_since_move_ = 0;
};

class TinyCamera final : public drivers::TofCamera {
 public:
  void configure(const drivers::TofSettings&) override {}
  drivers::TofSettings settings() const override { return {}; }
  drivers::TofFrame acquire() override { return tinyFrame(); }
  std::string deviceString() const override { return "tiny camera"; }
  std::uint32_t serial() const override { return 1; }
};

}  // namespace

// The issue-51 flake of cli.modbus_turntable (the 240° row read 239.995): a still table that has not
// yet reported "in position" was taken as settled, and its settling jitter became the view's angle.
TEST(Capture, AViewWaitsForInPositionNotJustStill) {
  const test::ScratchFolder scratch("settling");
  dataset::Dataset ds(scratch.path.string());
  SettlingTable table;
  TinyCamera camera;
  rig::CaptureOptions o;
  o.cls = "mug";
  o.instance = "settling";
  o.elevation_label = "30";
  o.step_deg = 120;
  o.settle_s = 0;  // the pose source's own bit is the settling window
  o.discard_frames = 0;
  EXPECT_EQ(rig::runCapture(camera, table, ds, o).written, 3u);
  const auto views = dataset::Dataset::readManifest(ds.root());
  ASSERT_EQ(views.size(), 3u);
  for (const auto& v : views) EXPECT_EQ(v.measured_deg, v.key.commanded_deg) << v.key.commanded_deg;
}

TEST(Dataset, VerifyFindsMissingCorruptAndOrphanFiles) {
  const keyturn::test::ScratchFolder scratch("ds");
  const std::filesystem::path& root = scratch.path;
  dataset::Dataset ds(root.string());
  const drivers::TofFrame f = tinyFrame();
  for (double a : {0.0, 5.0, 10.0}) rig::writeFrameView(ds, {"box", "b1", "45", a}, dataset::ViewMetadata(), f);
  EXPECT_TRUE(dataset::Dataset::verify(root.string()).ok());
  EXPECT_THROW(rig::writeFrameView(ds, {"box", "b1", "45", 5.0}, dataset::ViewMetadata(), f), Error);  // never twice

  fs::remove(root / "box/b1/e45/a5.0_amplitude.png");
  std::ofstream(root / "box/b1/e45/a10.0.json", std::ios::app) << " ";
  std::ofstream(root / "box/b1/e45/stray.pcd") << "x";
  const auto r = dataset::Dataset::verify(root.string());
  EXPECT_EQ(r.views, 3u);
  EXPECT_EQ(r.missing, std::vector<std::string>{"box/b1/e45/a5.0_amplitude.png"});
  EXPECT_EQ(r.corrupt, std::vector<std::string>{"box/b1/e45/a10.0.json"});
  EXPECT_EQ(r.orphans, std::vector<std::string>{"box/b1/e45/stray.pcd"});
  EXPECT_FALSE(r.ok());
}

TEST(Dataset, TheStudiosSnapshotsAreTheDatasetsOwnNotOrphans) {
  const keyturn::test::ScratchFolder scratch("snap");
  const std::filesystem::path& root = scratch.path;
  dataset::Dataset ds(root.string());
  const drivers::TofFrame f = tinyFrame();
  rig::writeFrameView(ds, {"box", "b1", "45", 0.0}, dataset::ViewMetadata(), f);
  // What the studio's Snapshot (Ctrl+S) writes: a PCD and its three PNGs in DATASET/snapshots/.
  rig::writeFrameFiles((root / dataset::kSnapshotsFolder / "20260101-120000-000.pcd").string(), f);
  const auto r = dataset::Dataset::verify(root.string());
  EXPECT_TRUE(r.orphans.empty()) << r.text(root.string());
  EXPECT_TRUE(r.good());
  // A class called "snapshots" keeps its views in subfolders: a stray file there is still an orphan.
  fs::create_directories(root / "snapshots/s1/e45");
  std::ofstream(root / "snapshots/s1/e45/stray.pcd") << "x";
  EXPECT_EQ(dataset::Dataset::verify(root.string()).orphans, std::vector<std::string>{"snapshots/s1/e45/stray.pcd"});
  fs::remove_all(root);
}

TEST(Dataset, AnAppendCutOffByACrashIsDroppedOnReopen) {
  const keyturn::test::ScratchFolder scratch("ds_cut");
  const std::filesystem::path& root = scratch.path;
  { dataset::Dataset ds(root.string()); }
  std::ofstream(root / "manifest.csv", std::ios::app) << "box,b1,45,45.000,0.000,0.0";  // no newline
  EXPECT_EQ(dataset::Dataset::verify(root.string()).bad_rows.size(), 1u);
  dataset::Dataset reopened(root.string());
  EXPECT_TRUE(reopened.views().empty());
  EXPECT_TRUE(dataset::Dataset::verify(root.string()).ok());
}
