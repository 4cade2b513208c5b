// The studio and the CLI open devices through rig's one factory: the same spec gives the same
// device whichever front end opens it (issue 31's "done when").
#include <gtest/gtest.h>

#include <cstdlib>

#include "keyturn/core/error.h"
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
