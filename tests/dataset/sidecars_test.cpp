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

using test::writeText;

const char* kMatrix = "[[1,0,0,0.1],[0,1,0,0.2],[0,0,1,0.7],[0,0,0,1]]";

}  // namespace

TEST(Sidecars, ReadTheTransformOrNoneWhenUncalibrated) {
  const keyturn::test::ScratchFolder scratch("sidecars");
  const std::filesystem::path& d = scratch.path;
  const auto m = dataset::readViewTransform(writeText(d / "a.json", std::string("{\"camera_from_turntable\": ") + kMatrix + "}"));
  ASSERT_TRUE(m.has_value());
  EXPECT_DOUBLE_EQ((*m)(2, 3), 0.7);
  EXPECT_DOUBLE_EQ((*m)(0, 0), 1.0);
  EXPECT_FALSE(dataset::readViewTransform(writeText(d / "b.json", "{\"camera_from_turntable\": null}")).has_value());

  const std::string cal = writeText(d / "cal.json", std::string("{\"format\": \"keyturn-axis-calibration\", "
                                                            "\"camera_from_turntable\": ") + kMatrix + "}");
  EXPECT_DOUBLE_EQ(dataset::readAxisCalibration(cal)(1, 3), 0.2);
  const Eigen::Matrix4d adopted = dataset::adoptAxisCalibration(cal, (d / "ds").string());
  EXPECT_DOUBLE_EQ(adopted(0, 3), 0.1);
  EXPECT_DOUBLE_EQ(dataset::readAxisCalibration((d / "ds" / "calibration.json").string())(2, 3), 0.7) << "a copy kept";
}

TEST(Sidecars, EachBadFileIsOneLineNamingIt) {
  const keyturn::test::ScratchFolder scratch("sidecars_bad");
  const std::filesystem::path& d = scratch.path;
  const auto err = [&](const std::string& name, const std::string& text) {
    const std::string p = writeText(d / name, text);
    return test::errorOf([&] { dataset::readViewTransform(p); });
  };
  EXPECT_EQ(err("a.json", "{not json"),
            (d / "a.json").string() + ": not JSON at byte 3 (invalid literal; last read: '{no'; expected string literal)");
  EXPECT_EQ(err("b.json", "{}"), (d / "b.json").string() + ": not a keyturn view sidecar");
  EXPECT_EQ(err("c.json", "{\"camera_from_turntable\": [[1,2],[3,4]]}"),
            (d / "c.json").string() + ": camera_from_turntable must be a 4 × 4 array");
  EXPECT_EQ(err("d.json", "{\"camera_from_turntable\": [[1,0,0,0],[0,1,0,0],[0,0,1,\"x\"],[0,0,0,1]]}"),
            (d / "d.json").string() + ": camera_from_turntable holds a non-number");
  EXPECT_EQ(test::errorOf([&] { dataset::readViewTransform((d / "none.json").string()); }),
            (d / "none.json").string() + ": cannot read (No such file or directory)");
  const std::string wrong = writeText(d / "e.json", "{\"format\": \"other\"}");
  EXPECT_EQ(test::errorOf([&] { dataset::readAxisCalibration(wrong); }), wrong + ": not a keyturn axis calibration");
}
