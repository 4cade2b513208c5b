// A capture killed in the middle of a view's writes, then resumed: what a SIGKILL leaves at each
// step (a temporary half written, a view's files renamed into place without their row, a file of an
// earlier take that the retake does not write) is cleaned up by the resume, and the dataset verifies.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <unistd.h>

#include "keyturn/dataset/dataset.h"
#include "keyturn/rig/captured_views.h"
#include "support/scratch_path.h"

namespace fs = std::filesystem;
using namespace keyturn;

namespace {

drivers::TofFrame frame(bool with_confidence, float z) {
  drivers::TofFrame f;
  f.width = 2;
  f.height = 2;
  f.distance.assign(4, 1000);
  f.amplitude.assign(4, 500);
  if (with_confidence) f.confidence.assign(4, 65535);
  f.cloud.width = 2;
  f.cloud.height = 2;
  f.cloud.points.assign(4, Eigen::Vector3f(0.f, 0.f, z));
  return f;
}

void plant(const fs::path& p, const std::string& bytes) { std::ofstream(p, std::ios::binary | std::ios::trunc) << bytes; }

std::size_t filesIn(const fs::path& dir) {
  std::size_t n = 0;
  for (const auto& e : fs::directory_iterator(dir)) n += e.is_regular_file();
  return n;
}

}  // namespace

TEST(InterruptedCapture, AResumeRemovesTheLeftoversAndRetakesTheViewCleanly) {
  const keyturn::test::ScratchFolder scratch("interrupted");
  const std::filesystem::path& root = scratch.path;
  const fs::path e30 = root / "mug/builtin/e30";
  {
    dataset::Dataset ds(root.string());
    for (double a : {35.0, 40.0}) rig::writeFrameView(ds, {"mug", "builtin", "30", a}, dataset::ViewMetadata(), frame(true, 1.f));
    // An earlier take of 45° that got as far as its files (one of them a confidence map), then a
    // second take killed in each writer: the files of the first are under their final names
    // without a row, the second's temporaries half written.
    rig::writeFrameView(ds, {"mug", "builtin", "30", 45.0}, dataset::ViewMetadata(), frame(true, 2.f));
  }
  {
    // Cut 45°'s row, as a kill between its files and its row leaves the dataset.
    std::ifstream in(root / "manifest.csv");
    std::string header, row35, row40;
    std::getline(in, header), std::getline(in, row35), std::getline(in, row40);
    plant(root / "manifest.csv", header + "\n" + row35 + "\n" + row40 + "\n");
  }
  plant(e30 / "a45.0.pcd.tmp.Ab12Cd", "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIE");  // saveCloud killed
  plant(e30 / "a45.0_amplitude.png.tmp.x9Y8z7.png", "\x89PNG\r\n");                            // savePng16 killed
  plant(e30 / "a45.0.json.tmp.QwErT1", "{\n  \"class\": \"mu");                                 // the sidecar's
  plant(root / "manifest.csv.tmp.Zz00Yy", "class,instance");  // the repair of a cut row
  plant(e30 / "a40.0_distance.tmp.png", "\x89PNG");            // an older keyturn's fixed name

  const dataset::VerifyReport before = dataset::Dataset::verify(root.string());
  EXPECT_EQ(before.views, 2u);
  EXPECT_EQ(before.temporaries.size(), 5u) << "named apart from the orphans";
  EXPECT_EQ(before.orphans.size(), 5u) << "45°'s files from the first take: its pcd, three PNGs and sidecar";
  EXPECT_NE(before.text(root.string()).find("5 leftover temporary files from an interrupted write"), std::string::npos)
      << before.text(root.string());

  dataset::Dataset resumed(root.string());
  EXPECT_EQ(resumed.temporariesRemoved(), 5u);
  ASSERT_FALSE(resumed.has({"mug", "builtin", "30", 45.0}));
  // The retake's camera gives no confidence map: the first take's must not stay behind as an orphan.
  const dataset::ViewRecord r = rig::writeFrameView(resumed, {"mug", "builtin", "30", 45.0}, dataset::ViewMetadata(), frame(false, 3.f));
  EXPECT_EQ(r.files.size(), 4u);
  EXPECT_FALSE(fs::exists(e30 / "a45.0_confidence.png"));
  EXPECT_EQ(filesIn(e30), 5u + 5u + 4u) << "35° and 40° whole, 45° retaken, nothing else";

  const dataset::VerifyReport after = dataset::Dataset::verify(root.string());
  EXPECT_TRUE(after.good()) << after.text(root.string());
  EXPECT_EQ(after.views, 3u);
  EXPECT_TRUE(after.temporaries.empty());
  EXPECT_TRUE(after.orphans.empty());
  EXPECT_EQ(dataset::Dataset::readManifest(root.string()).size(), 3u) << "one row a view";
  fs::remove_all(root);
}

TEST(InterruptedCapture, LeftoverTemporariesAloneLeaveTheViewsVerified) {
  const keyturn::test::ScratchFolder scratch("interrupted_only");
  const std::filesystem::path& root = scratch.path;
  {
    dataset::Dataset d(root.string());
    rig::writeFrameView(d, {"mug", "builtin", "30", 0.0}, dataset::ViewMetadata(), frame(true, 1.f));
  }
  plant(root / "mug/builtin/e30/a5.0.json.tmp.Ab12Cd", "{");
  const dataset::VerifyReport r = dataset::Dataset::verify(root.string());
  EXPECT_TRUE(r.good()) << "every view whole: the leftover is not part of the dataset";
  EXPECT_TRUE(r.orphans.empty());
  EXPECT_EQ(r.temporaries, std::vector<std::string>{"mug/builtin/e30/a5.0.json.tmp.Ab12Cd"});
  const std::string text = r.text(root.string());
  EXPECT_NE(text.find("temporary: mug/builtin/e30/a5.0.json.tmp.Ab12Cd\n"
                      "1 leftover temporary file from an interrupted write (not part of any view; the next capture "
                      "removes them)\n"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("1 views, 0 missing, 0 corrupt, 0 orphan, 0 duplicate files — OK"), std::string::npos) << text;
  fs::remove_all(root);
}
