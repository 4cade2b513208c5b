// The studio and the CLI open devices through rig's one factory: the same spec gives the same
// device whichever front end opens it (issue 31's "done when").
#include <gtest/gtest.h>

#include <cstdlib>

#include "keyturn/core/error.h"
#include "keyturn/core/json_file.h"
#include "keyturn/rig/device_factory.h"
#include "keyturn/studio/studio_rig_factory.h"

namespace keyturn {
namespace {

// The CLI's path (keyturn grab --camera TEXT): the text parsed, then rig's factory.
std::unique_ptr<drivers::TofCamera> openAsTheCliDoes(const std::string& text, rig::DeviceFactory& factory) {
  return factory.openCamera(rig::CameraSpec::parse(text));
}

TEST(StudioDevices, TheStudiosSimulatedCameraIsTheOneTheCliOpensFromTheSameSpec) {
  ::setenv("MESASR_SIM_CONFIG", "/nonexistent/keyturn-must-not-read-this.json", 1);
  studio::StudioRigFactory studio(std::string(KEYTURN_DATA_DIR) + "/objects/objects.csv");
  ASSERT_GE(studio.simObjects().size(), 2u);
  const std::string object = studio.simObjects()[1].instance;
  const rig::CameraSpec spec = studio.simulatedCamera(object);
  ASSERT_EQ(spec.kind, rig::CameraSpec::Kind::Simulated);
  ASSERT_FALSE(spec.sim_config.empty());

  auto in_studio = studio.openCamera(spec, {});
  rig::DeviceFactory cli;
  auto in_cli = openAsTheCliDoes(spec.toString(), cli);
  EXPECT_EQ(in_cli->deviceString(), in_studio->deviceString());
  EXPECT_EQ(in_cli->serial(), in_studio->serial());
  ASSERT_TRUE(studio.cameraFromTurntable() && cli.cameraFromTurntable());
  EXPECT_TRUE(studio.cameraFromTurntable()->isApprox(*cli.cameraFromTurntable(), 1e-12));
  // The same scene, noise and all: the first frames are equal pixel for pixel.
  const drivers::TofFrame a = in_studio->acquire(), b = in_cli->acquire();
  EXPECT_EQ(a.distance, b.distance);
  EXPECT_EQ(a.amplitude, b.amplitude);
  EXPECT_GT(a.cloud.validCount(), 1000u);

  // Another object is another device: the test can tell them apart.
  auto other = studio.openCamera(studio.simulatedCamera(studio.simObjects()[0].instance), {});
  EXPECT_NE(other->acquire().distance, a.distance);
  ::unsetenv("MESASR_SIM_CONFIG");
}

// The simulated OpenNI2 camera's default device, chosen in the studio, looks at the studio's own
// simulated rig: the chosen object's mesh on the studio's turntable (before, its built-in mug,
// which no model was trained on), through the same configuration file format the CLI writes.
TEST(StudioDevices, TheSimulatedOpenNi2CameraLooksAtTheStudiosObjectAndTurntable) {
  studio::StudioRigFactory studio(std::string(KEYTURN_DATA_DIR) + "/objects/objects.csv");
  const studio::SimObject object = studio.simObjects()[1];
  const rig::CameraSpec spec = studio.simulatedOpenNi2Camera(object.instance);
  ASSERT_EQ(spec.kind, rig::CameraSpec::Kind::OpenNi2);
  const std::string scheme = "keyturn-sim://";
  ASSERT_EQ(spec.openni2_uri.rfind(scheme + "/", 0), 0u) << spec.openni2_uri;  // a configuration file's path
  const std::string config = spec.openni2_uri.substr(scheme.size());
  const nlohmann::json j = readJsonFile(config);
  EXPECT_EQ(j.at("mesh").get<std::string>(), object.mesh);
  EXPECT_EQ(j.at("world").get<std::string>(), studio.runtimeDir() + "/world.json");
  EXPECT_EQ(j.at("frame_rate").get<double>(), 30.0);
  EXPECT_EQ(rig::CameraSpec::parse(spec.toString()), spec);  // the CLI's text form opens the same device
  // The SR4000's spec still gets its own rate from the same file.
  const rig::CameraSpec sr4000 = studio.simulatedCamera(object.instance);
  EXPECT_EQ(readJsonFile(sr4000.sim_config).at("frame_rate").get<double>(), 50.0);
}

TEST(StudioDevices, ARealCameraSpecFailsTheSameWayInBoth) {
  // No MESA library here: both front ends name the same missing library in the same line.
  studio::StudioRigFactory studio(std::string(KEYTURN_DATA_DIR) + "/objects/objects.csv");
  const rig::CameraSpec spec = rig::CameraSpec::parse("usb:4000123,lib=/nonexistent/libmesasr.so");
  std::string from_studio, from_cli;
  try {
    studio.openCamera(spec, {});
  } catch (const Error& e) {
    from_studio = e.what();
  }
  try {
    rig::DeviceFactory cli;
    openAsTheCliDoes(spec.toString(), cli);
  } catch (const Error& e) {
    from_cli = e.what();
  }
  EXPECT_NE(from_studio.find("/nonexistent/libmesasr.so"), std::string::npos) << from_studio;
  EXPECT_EQ(from_studio, from_cli);
}

}  // namespace
}  // namespace keyturn
