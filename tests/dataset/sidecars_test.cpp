// A dataset's small JSON files: a view's transform, the axis calibration, each bad file one line.
#include "keyturn/dataset/sidecars.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "support/error_of.h"
#include "support/scratch_path.h"

using namespace keyturn;
namespace fs = std::filesystem;

namespace {

std::string write(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p) << text;
  return p.string();
}

const char* kMatrix = "[[1,0,0,0.1],[0,1,0,0.2],[0,0,1,0.7],[0,0,0,1]]";

}  // namespace

TEST(Sidecars, ReadTheTransformOrNoneWhenUncalibrated) {
  const fs::path d = keyturn::test::scratchPath("sidecars");
  fs::remove_all(d);
  const auto m = dataset::readViewTransform(write(d / "a.json", std::string("{\"camera_from_turntable\": ") + kMatrix + "}"));
  ASSERT_TRUE(m.has_value());
  EXPECT_DOUBLE_EQ((*m)(2, 3), 0.7);
  EXPECT_DOUBLE_EQ((*m)(0, 0), 1.0);
  EXPECT_FALSE(dataset::readViewTransform(write(d / "b.json", "{\"camera_from_turntable\": null}")).has_value());

  const std::string cal = write(d / "cal.json", std::string("{\"format\": \"keyturn-axis-calibration\", "
                                                            "\"camera_from_turntable\": ") + kMatrix + "}");
  EXPECT_DOUBLE_EQ(dataset::readAxisCalibration(cal)(1, 3), 0.2);
  const Eigen::Matrix4d adopted = dataset::adoptAxisCalibration(cal, (d / "ds").string());
  EXPECT_DOUBLE_EQ(adopted(0, 3), 0.1);
  EXPECT_DOUBLE_EQ(dataset::readAxisCalibration((d / "ds" / "calibration.json").string())(2, 3), 0.7) << "a copy kept";
}

TEST(Sidecars, EachBadFileIsOneLineNamingIt) {
  const fs::path d = keyturn::test::scratchPath("sidecars_bad");
  fs::remove_all(d);
  const auto err = [&](const std::string& name, const std::string& text) {
    const std::string p = write(d / name, text);
    return test::errorOf([&] { dataset::readViewTransform(p); });
  };
  EXPECT_EQ(err("a.json", "{not json").rfind((d / "a.json").string() + ": not valid JSON: ", 0), 0u);
  EXPECT_EQ(err("b.json", "{}"), (d / "b.json").string() + ": not a keyturn view sidecar");
  EXPECT_EQ(err("c.json", "{\"camera_from_turntable\": [[1,2],[3,4]]}"),
            (d / "c.json").string() + ": camera_from_turntable must be a 4 × 4 array");
  EXPECT_EQ(err("d.json", "{\"camera_from_turntable\": [[1,0,0,0],[0,1,0,0],[0,0,1,\"x\"],[0,0,0,1]]}"),
            (d / "d.json").string() + ": camera_from_turntable holds a non-number");
  EXPECT_EQ(test::errorOf([&] { dataset::readViewTransform((d / "none.json").string()); }),
            (d / "none.json").string() + ": no such view sidecar");
  const std::string wrong = write(d / "e.json", "{\"format\": \"other\"}");
  EXPECT_EQ(test::errorOf([&] { dataset::readAxisCalibration(wrong); }), wrong + ": not a keyturn axis calibration");
}

// A captured view's sidecar records its camera (Dataset::writeCaptured) and reads back the same; a
// field the sidecar lacks stays empty (the camera's default applies: rig::readViewCamera), an imported
// view records none, and a field of the wrong type is one line naming the file.
TEST(Sidecars, TheCameraRecordedIsTheCameraReadBack) {
  const fs::path d = keyturn::test::scratchPath("sidecars_camera");
  fs::remove_all(d);
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
    write(pcd, "not read here");
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

  const auto some = dataset::readSidecarCamera(write(d / "some.json", R"({"camera": {"device": "sim", "integration_time": 9}})"));
  EXPECT_EQ(some.camera.device, "sim");
  EXPECT_EQ(some.camera.integration_time, 9);
  EXPECT_FALSE(some.camera.modulation_mhz.has_value());
  EXPECT_FALSE(some.camera.acquire_mode.has_value());
  const auto imported = dataset::readSidecarCamera(write(d / "imported.json", R"({"imported_by": "keyturn import folders"})"));
  EXPECT_TRUE(imported.imported);
  EXPECT_EQ(imported.camera.device, "");
  const std::string bad = write(d / "bad.json", R"({"camera": {"auto_exposure": "yes"}})");
  EXPECT_EQ(test::errorOf([&] { dataset::readSidecarCamera(bad); }).rfind(bad + ": camera: ", 0), 0u);
}
