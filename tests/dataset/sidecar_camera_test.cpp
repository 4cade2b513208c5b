// A captured view's camera in its sidecar: Dataset::writeCaptured records it, readSidecarCamera reads it back.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "keyturn/dataset/dataset.h"
#include "keyturn/dataset/sidecars.h"
#include "support/error_of.h"
#include "support/scratch_path.h"

using namespace keyturn;
namespace fs = std::filesystem;

namespace {

using test::writeText;

}  // namespace

// A captured view's sidecar records its camera (Dataset::writeCaptured) and reads back the same; a
// field the sidecar lacks stays empty (the camera's default applies: rig::readViewCamera), an imported
// view records none, and a field of the wrong type is one line naming the file.
TEST(SidecarCamera, TheCameraRecordedIsTheCameraReadBack) {
  const keyturn::test::ScratchFolder scratch("sidecars_camera");
  const std::filesystem::path& d = scratch.path;
  dataset::Dataset ds((d / "ds").string());
  dataset::SidecarCamera cam;
  cam.device = "usb:4000123";
  cam.serial = 4000123;
  cam.modulation_mhz = 29.0;
  cam.integration_time = 42;
  cam.auto_exposure = false;
  cam.amplitude_threshold = 77;
  cam.acquire_mode = 0x911;
  std::string written;
  const auto r = ds.writeCaptured({"box", "b1", "30", 15.0}, dataset::ViewMetadata(), cam, [&](const std::string& pcd) {
    written = pcd;
    writeText(pcd, "not read here");
    return std::vector<std::string>{pcd};
  });
  EXPECT_EQ(written, (d / "ds" / "box" / "b1" / "e30" / "a15.0.pcd").string());
  EXPECT_EQ(r.files, (std::vector<std::string>{"box/b1/e30/a15.0.pcd", "box/b1/e30/a15.0.json"}));
  const auto back = dataset::readSidecarCamera((d / "ds" / r.sidecar()).string());
  EXPECT_FALSE(back.imported);
  EXPECT_EQ(back.camera.device, "usb:4000123");
  EXPECT_EQ(back.camera.serial, 4000123u);
  EXPECT_EQ(back.camera.modulation_mhz, 29.0);
  EXPECT_EQ(back.camera.integration_time, 42);
  EXPECT_EQ(back.camera.auto_exposure, false);
  EXPECT_EQ(back.camera.amplitude_threshold, 77);
  EXPECT_EQ(back.camera.acquire_mode, 0x911u);
  EXPECT_TRUE(dataset::Dataset::verify((d / "ds").string()).good());

  const auto some = dataset::readSidecarCamera(writeText(d / "some.json", R"({"camera": {"device": "sim", "integration_time": 9}})"));
  EXPECT_EQ(some.camera.device, "sim");
  EXPECT_EQ(some.camera.integration_time, 9);
  EXPECT_FALSE(some.camera.modulation_mhz.has_value());
  EXPECT_FALSE(some.camera.acquire_mode.has_value());
  const auto imported = dataset::readSidecarCamera(writeText(d / "imported.json", R"({"imported_by": "keyturn import folders"})"));
  EXPECT_TRUE(imported.imported);
  EXPECT_EQ(imported.camera.device, "");
  const std::string bad = writeText(d / "bad.json", R"({"camera": {"auto_exposure": "yes"}})");
  EXPECT_EQ(test::errorOf([&] { dataset::readSidecarCamera(bad); }).rfind(bad + ": camera: ", 0), 0u);
}
