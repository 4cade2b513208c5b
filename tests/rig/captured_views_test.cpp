// A camera frame written as a dataset's view and its camera read back as the camera's settings:
// what playback takes the view again with.
#include "keyturn/rig/captured_views.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "keyturn/dataset/sidecars.h"
#include "support/error_of.h"
#include "support/scratch_path.h"

using namespace keyturn;
namespace fs = std::filesystem;

TEST(CapturedViews, AFrameWrittenAsAViewReadsBackWithItsCamerasSettings) {
  const keyturn::test::ScratchFolder scratch("captured_views");
  const std::filesystem::path& d = scratch.path;
  dataset::Dataset ds(d.string());
  drivers::TofFrame f;
  f.width = f.height = 2;
  f.distance.assign(4, 1000);
  f.amplitude.assign(4, 500);
  f.cloud.width = f.cloud.height = 2;
  f.cloud.points.assign(4, Eigen::Vector3f(0.f, 0.f, 1.f));
  f.device = "usb:4000123";
  f.serial = 4000123;
  f.settings.modulation_frequency = drivers::modulationIndex(29.0);
  f.settings.integration_time = 42;
  f.settings.auto_exposure.enabled = false;
  f.settings.amplitude_threshold = 77;
  f.settings.acquire_mode = 0x911;
  const auto r = rig::writeFrameView(ds, {"box", "b1", "30", 0.0}, dataset::ViewMetadata(), f);
  // The PCD, the distance and amplitude PNGs (no confidence map), the sidecar.
  EXPECT_EQ(r.files, (std::vector<std::string>{"box/b1/e30/a0.0.pcd", "box/b1/e30/a0.0_distance.png",
                                               "box/b1/e30/a0.0_amplitude.png", "box/b1/e30/a0.0.json"}));
  const rig::ViewCamera cam = rig::readViewCamera((d / r.sidecar()).string());
  EXPECT_FALSE(cam.imported);
  EXPECT_EQ(cam.device, "usb:4000123");
  EXPECT_EQ(cam.serial, 4000123u);
  EXPECT_EQ(cam.settings.modulation_frequency, drivers::modulationIndex(29.0));
  EXPECT_EQ(cam.settings.integration_time, 42);
  EXPECT_FALSE(cam.settings.auto_exposure.enabled);
  EXPECT_EQ(cam.settings.amplitude_threshold, 77);
  EXPECT_EQ(cam.settings.acquire_mode, 0x911u);
  EXPECT_THROW(rig::writeFrameView(ds, {"box", "b1", "30", 0.0}, dataset::ViewMetadata(), f), Error);  // never twice

  // What a sidecar lacks is the camera's default; a frequency the camera lacks names the file.
  const fs::path partial = d / "partial.json";
  std::ofstream(partial) << R"({"camera": {"device": "sim", "integration_time": 9}})";
  const rig::ViewCamera some = rig::readViewCamera(partial.string());
  EXPECT_EQ(some.settings.integration_time, 9);
  EXPECT_EQ(some.settings.modulation_frequency, drivers::TofSettings().modulation_frequency);
  EXPECT_EQ(some.settings.acquire_mode, drivers::TofSettings().acquire_mode);
  const fs::path odd = d / "odd.json";
  std::ofstream(odd) << R"({"camera": {"modulation_mhz": 33.3}})";
  EXPECT_EQ(test::errorOf([&] { rig::readViewCamera(odd.string()); }).rfind(odd.string() + ": camera: ", 0), 0u);
}
