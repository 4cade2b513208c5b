// The one device factory (rig/device_factory.h): simulated cameras configured through their
// spec, never the environment, and the pose sources that belong with a camera.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "keyturn/rig/device_factory.h"
#include "keyturn/rig/simulated_rig.h"
#include "keyturn/sim/mesasr_sim_config.h"
#include "support/error_of.h"
#include "support/scratch_path.h"

namespace fs = std::filesystem;

namespace keyturn {
namespace {

using test::errorOf;

class DeviceFactoryTest : public ::testing::Test {
 protected:
  void SetUp() override {
    // What an outside program would use; keyturn must not read it (nor change it).
    ::setenv("MESASR_SIM_CONFIG", (dir_ / "not-there.json").c_str(), 1);
  }
  void TearDown() override {
    ::unsetenv("MESASR_SIM_CONFIG");
  }
  std::string config(const std::string& name, const std::string& json) {
    const fs::path p = dir_ / name;
    std::ofstream(p) << json;
    return p.string();
  }
  const test::ScratchFolder scratch_{"device_factory"};
  const fs::path& dir_ = scratch_.made();
};

TEST_F(DeviceFactoryTest, TwoSimulatedCamerasWithTheirOwnConfigurationsInOneProcess) {
  const std::string mug = config("mug.json", R"({"mesh": "builtin:mug", "serial": 4000111, "elevation": 30})");
  const std::string ball =
      config("ball.json", R"({"mesh": "builtin:sphere-target", "serial": 4000222, "elevation": 60, "distance": 0.9})");
  rig::DeviceFactory factory;
  auto a = factory.openCamera(rig::CameraSpec::parse("sim:" + mug));
  const auto a_pose = factory.cameraFromTurntable();
  auto b = factory.openCamera(rig::CameraSpec::parse("sim:" + ball));
  const auto b_pose = factory.cameraFromTurntable();
  EXPECT_EQ(a->serial(), 4000111u);
  EXPECT_EQ(b->serial(), 4000222u);
  // Each keeps its own scene: frames taken in turn differ, and a reads the mug again after b opened.
  const drivers::TofFrame fa = a->acquire(), fb = b->acquire(), fa2 = a->acquire();
  EXPECT_EQ(fa.serial, 4000111u);
  EXPECT_EQ(fb.serial, 4000222u);
  EXPECT_NE(fa.distance, fb.distance);
  EXPECT_EQ(fa2.serial, 4000111u);
  // Exact camera poses from each configuration: 30° and 60° above the table.
  ASSERT_TRUE(a_pose && b_pose);
  EXPECT_GT(((*a_pose) - (*b_pose)).norm(), 0.1);
  EXPECT_STREQ(std::getenv("MESASR_SIM_CONFIG"), (dir_ / "not-there.json").c_str());  // left as it was
}

TEST_F(DeviceFactoryTest, SimWithoutAConfigurationIsTheSimulatorsDefaultsNotTheEnvironments) {
  rig::DeviceFactory factory;
  auto camera = factory.openCamera(rig::CameraSpec::parse("sim"));  // $MESASR_SIM_CONFIG names no file: not read
  EXPECT_EQ(camera->serial(), sim::MesaSrSimConfig().serial);
  EXPECT_EQ(camera->acquire().cloud.width, 176u);
}

TEST_F(DeviceFactoryTest, ABadConfigurationOrMeshIsNamedBeforeTheSimulatorOpens) {
  const std::string nomesh = config("nomesh.json", R"({"mesh": "nowhere.ply"})");
  rig::DeviceFactory factory;
  const std::string e = errorOf([&] { factory.openCamera(rig::CameraSpec::parse("sim:" + nomesh)); });
  EXPECT_EQ(e.rfind(nomesh + ": mesh: ", 0), 0u) << e;
  EXPECT_EQ(errorOf([&] { factory.openCamera(rig::CameraSpec::parse("sim:" + (dir_ / "none.json").string())); }),
            (dir_ / "none.json").string() + ": cannot read (No such file or directory)");
}

TEST_F(DeviceFactoryTest, PoseSourcesThatBelongWithACameraAreRefusedWithoutIt) {
  rig::DeviceFactory factory;  // no simulated rig set up, no recording played
  EXPECT_EQ(errorOf([&] { factory.openPoseSource(rig::PoseSpec::parse("sim")); }),
            "pose 'sim': the simulated turntable shares the simulated camera's world, and none was set up here");
  EXPECT_EQ(errorOf([&] { factory.openPoseSource(rig::PoseSpec::parse("playback")); }),
            "pose 'playback' needs camera playback:DATASET (the recording holds both)");
  EXPECT_EQ(errorOf([&] { factory.openPoseSource(rig::PoseSpec::parse("can:vcan0")); }),
            "pose 'can:vcan0' needs the CANopen axes file as its profile (can:IFACE,profile=AXES.json; see "
            "docs/protocols.md)");
}

TEST_F(DeviceFactoryTest, TheSimulatedTurntableTurnsTheSimulatedCamerasScene) {
  rig::SimulatedCameraOptions o;
  o.world = (dir_ / "world.json").string();
  const rig::CameraSpec spec = rig::writeSimulatedCameraConfig((dir_ / "rig" / "camera.json").string(), o);
  EXPECT_EQ(spec.toString(), "sim:" + (dir_ / "rig" / "camera.json").string());
  sim::TurntableServerOptions table;
  table.world_file = o.world;
  table.motion = rig::captureMotion(true);
  rig::DeviceFactory factory(table);
  auto turntable = factory.openPoseSource(rig::PoseSpec::parse("sim"));
  auto camera = factory.openCamera(spec);
  const drivers::TofFrame at0 = camera->acquire();
  turntable->moveTo(90);
  (void)drivers::waitInPosition(*turntable, 5);
  const drivers::TofFrame at90 = camera->acquire();
  EXPECT_NEAR(turntable->read().turntable_deg, 90, 0.5);
  EXPECT_NE(at0.distance, at90.distance);  // the mug's handle has moved
}

}  // namespace
}  // namespace keyturn
