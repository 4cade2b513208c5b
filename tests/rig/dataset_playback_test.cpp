// A dataset replayed as a camera and a pose source: frames in manifest order, their recorded poses
// and settings, rates, looping, seeking by angle, and the errors a user meets.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "support/error_of.h"
#include "keyturn/dataset/dataset.h"
#include "keyturn/rig/captured_views.h"
#include "keyturn/rig/dataset_playback.h"
#include "support/scratch_path.h"

namespace fs = std::filesystem;
using namespace keyturn;
using test::errorOf;

namespace {

constexpr double kAngles[] = {0.0, 5.0, 10.0, 15.0};

// View k: every pixel at z = 0.5 + 0.1 k m, raw distance 1000 + k, amplitude 200 + k.
drivers::TofFrame frame(int k) {
  drivers::TofFrame f;
  f.width = 4;
  f.height = 3;
  f.distance.assign(12, static_cast<std::uint16_t>(1000 + k));
  f.amplitude.assign(12, static_cast<std::uint16_t>(200 + k));
  f.confidence.assign(12, 65535);
  f.cloud.width = 4;
  f.cloud.height = 3;
  f.cloud.points.assign(12, Eigen::Vector3f(0.01f * static_cast<float>(k), 0.f, 0.5f + 0.1f * static_cast<float>(k)));
  f.cloud.points[5] = Eigen::Vector3f::Constant(std::nanf(""));  // no return
  f.distance[5] = 0;
  f.cloud.amplitude.assign(12, 200.f + static_cast<float>(k));
  f.cloud.confidence.assign(12, 1.f);
  f.device = "SR4000 test";
  f.serial = 4000123;
  f.settings.integration_time = 55;
  f.settings.modulation_frequency = 3;  // 15 MHz
  f.settings.amplitude_threshold = 7;
  return f;
}

class Playback : public ::testing::Test {
 protected:
  void SetUp() override {
    dataset::Dataset ds(root_);
    for (int k = 0; k < 4; ++k) {
      dataset::ViewMetadata m;
      m.elevation_deg = 30;
      m.measured_deg = kAngles[k] + 0.03 * (k + 1);
      rig::writeFrameView(ds, {"mug", "m1", "30", kAngles[k]}, m, frame(k));
    }
    stampViews({0.0, 0.25, 0.5, 0.75});
  }

  // Rewrites the manifest's captured_at column (seconds after 2026-11-22T00:00:00Z); "" leaves no stamp.
  void stampViews(const std::vector<double>& seconds, bool blank = false) {
    std::ifstream in(root_ + "/manifest.csv");
    std::string line, out;
    std::getline(in, line);
    out = line + "\n";
    for (std::size_t i = 0; std::getline(in, line); ++i) {
      std::vector<std::string> c;
      std::stringstream s(line);
      for (std::string cell; std::getline(s, cell, ',');) c.push_back(cell);
      char stamp[40];
      std::snprintf(stamp, sizeof stamp, "2026-11-22T%02d:%02d:%06.3fZ", static_cast<int>(seconds[i] / 3600),
                    static_cast<int>(seconds[i] / 60) % 60, std::fmod(seconds[i], 60.0));
      c[6] = blank ? "" : stamp;
      for (std::size_t j = 0; j < c.size(); ++j) out += (j ? "," : "") + c[j];
      out += "\n";
    }
    std::ofstream(root_ + "/manifest.csv") << out;
  }

  std::shared_ptr<rig::Recording> recording(double rate = 1000, bool loop = true) {
    return std::make_shared<rig::Recording>(root_, rig::PlaybackOptions{rate, loop});
  }

  const keyturn::test::ScratchFolder scratch_{"playback"};
  const std::string root_ = scratch_.path.string();
};

}  // namespace

TEST_F(Playback, DeliversTheViewsInManifestOrderWithTheirRecordedPoses) {
  auto rec = recording();
  rig::PlaybackCamera camera(rec);
  rig::PlaybackPose pose(rec);
  const auto views = dataset::Dataset::readManifest(root_);
  for (int k = 0; k < 4; ++k) {
    const drivers::TofFrame f = camera.acquire();
    EXPECT_EQ(f.sequence, static_cast<std::uint64_t>(k + 1));
    ASSERT_EQ(f.width * f.height, 12u);
    EXPECT_EQ(f.distance[0], 1000 + k);
    EXPECT_EQ(f.distance[5], 0);
    EXPECT_EQ(f.amplitude[3], 200 + k);
    EXPECT_FLOAT_EQ(f.cloud.points[0].z(), 0.5f + 0.1f * static_cast<float>(k));
    EXPECT_TRUE(std::isnan(f.cloud.points[5].x()));
    EXPECT_EQ(f.device, "SR4000 test");
    EXPECT_EQ(f.serial, 4000123u);
    EXPECT_EQ(f.settings.integration_time, 55);
    EXPECT_EQ(f.settings.modulation_frequency, 3);
    // The pose is the one recorded with the frame shown: the manifest's and the sidecar's.
    const double deg = pose.read().turntable_deg;
    EXPECT_NEAR(deg, views[static_cast<std::size_t>(k)].measured_deg, 1e-9);
    std::ifstream sidecar(root_ + "/" + views[static_cast<std::size_t>(k)].sidecar());
    EXPECT_NEAR(deg, nlohmann::json::parse(sidecar)["measured_deg"].get<double>(), 1e-9);
    EXPECT_NEAR(deg, kAngles[k] + 0.03 * (k + 1), 1e-3);
  }
  EXPECT_EQ(camera.settings().amplitude_threshold, 7);
  EXPECT_EQ(camera.serial(), 4000123u);
  EXPECT_EQ(camera.deviceString(), "recording " + root_ + " (4 views, 1000 frames/s, looping)");
}

TEST_F(Playback, LoopsOrEndsWithTheManifestNamed) {
  rig::PlaybackCamera looping(recording());
  std::vector<int> seen;
  for (int i = 0; i < 9; ++i) seen.push_back(looping.acquire().distance[0] - 1000);
  EXPECT_EQ(seen, (std::vector<int>{0, 1, 2, 3, 0, 1, 2, 3, 0}));

  auto rec = recording(1000, false);
  rig::PlaybackCamera once(rec);
  for (int i = 0; i < 4; ++i) (void)once.acquire();
  EXPECT_FALSE(rec->ended());
  EXPECT_EQ(errorOf([&] { once.acquire(); }),
            root_ + "/manifest.csv: end of the recording after its 4 views (not looping)");
  EXPECT_THROW(once.acquire(), rig::EndOfRecording);  // not a camera lost: nothing to reconnect to
  EXPECT_TRUE(rec->ended());
  rec->rewind();
  EXPECT_FALSE(rec->ended());
  EXPECT_EQ(once.acquire().distance[0], 1000);
  EXPECT_EQ(once.acquire().sequence, 2u);
}

TEST_F(Playback, PlaysAtTheRecordedRateOrAChosenOne) {
  EXPECT_DOUBLE_EQ(recording(0)->frameRate(), 4.0);  // views 0.25 s apart
  // A capture resumed an hour later, or a view stamped before its predecessor: still 4 frames/s.
  stampViews({0.0, 0.25, 0.5, 3600.5});
  EXPECT_DOUBLE_EQ(recording(0)->frameRate(), 4.0);
  stampViews({0.0, 0.25, 0.5, 0.3});
  EXPECT_DOUBLE_EQ(recording(0)->frameRate(), 4.0);
  stampViews({0.0, 0.5, 1.0, 2.0});
  EXPECT_DOUBLE_EQ(recording(0)->frameRate(), 2.0);  // the median interval
  EXPECT_DOUBLE_EQ(recording(12.5)->frameRate(), 12.5);
  // Never faster than the rate: five frames at 20 frames/s span at least four intervals.
  rig::PlaybackCamera camera(recording(20));
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < 5; ++i) (void)camera.acquire();
  EXPECT_GE(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 4 / 20.0 - 1e-3);
  stampViews({0, 0, 0, 0}, true);
  EXPECT_EQ(errorOf([&] { recording(0); }), root_ +
                                                "/manifest.csv: the views' capture times give no rate (fewer than two "
                                                "distinct): choose a playback rate");
  EXPECT_EQ(errorOf([&] { recording(5); }), "");
}

TEST_F(Playback, AMoveSeeksTheNearestRecordedAngleAndHoldsThere) {
  auto rec = recording();
  rig::PlaybackCamera camera(rec);
  rig::PlaybackPose pose(rec);
  EXPECT_TRUE(pose.canMove());
  pose.moveTo(11.0);  // nearest recorded: 10°
  EXPECT_NEAR(pose.read().turntable_deg, 10.09, 1e-9);
  EXPECT_EQ(camera.acquire().distance[0], 1002);
  EXPECT_EQ(camera.acquire().distance[0], 1002);  // held, as a table stays where it was sent
  pose.moveTo(358.0);  // 2° from 0° round the circle
  EXPECT_EQ(camera.acquire().distance[0], 1000);
  pose.moveTo(15.0);
  pose.home();
  EXPECT_NEAR(pose.read().turntable_deg, 0.03, 1e-9);
  EXPECT_EQ(pose.describe(), "playback of " + root_);
}

TEST_F(Playback, NamesAMissingDatasetAViewFileGoneAndAnEmptyRecording) {
  EXPECT_EQ(errorOf([&] { rig::Recording r(root_ + "/nope", {}); }), root_ + "/nope: no such dataset to play back");
  fs::create_directories(root_ + "/empty");
  EXPECT_EQ(errorOf([&] { rig::Recording r(root_ + "/empty", {}); }),
            root_ + "/empty/manifest.csv: missing (not a keyturn dataset to play back)");
  dataset::Dataset(root_ + "/empty");  // a manifest without rows
  EXPECT_EQ(errorOf([&] { rig::Recording r(root_ + "/empty", {}); }),
            root_ + "/empty/manifest.csv: no views to play back");

  fs::remove(root_ + "/mug/m1/e30/a5.0_amplitude.png");
  rig::PlaybackCamera camera(recording());
  EXPECT_EQ(camera.acquire().distance[0], 1000);
  EXPECT_EQ(errorOf([&] { camera.acquire(); }),
            root_ + "/mug/m1/e30/a5.0_amplitude.png: missing (view mug/m1/e30/a5.0 of the recording)");
}

TEST_F(Playback, AViewWithoutImagesGetsThemFromItsCloud) {
  // As an import that references PCDs only: the PNGs are not there and the row lists the PCD alone.
  for (const char* png : {"_distance.png", "_amplitude.png", "_confidence.png"}) fs::remove(root_ + "/mug/m1/e30/a0.0" + png);
  std::ifstream in(root_ + "/manifest.csv");
  std::string header, first, rest, line;
  std::getline(in, header);
  std::getline(in, first);
  while (std::getline(in, line)) rest += line + "\n";
  std::vector<std::string> c;
  std::stringstream s(first);
  for (std::string cell; std::getline(s, cell, ',');) c.push_back(cell);
  c[7] = "mug/m1/e30/a0.0.pcd";
  c[8] = dataset::sha256File(root_ + "/" + c[7]);
  std::string row;
  for (std::size_t j = 0; j < c.size(); ++j) row += (j ? "," : "") + c[j];
  std::ofstream(root_ + "/manifest.csv") << header << "\n" << row << "\n" << rest;

  rig::PlaybackCamera camera(recording());
  const drivers::TofFrame f = camera.acquire();
  // 0.5 m of the default 30 MHz's 4.997 m range; the amplitude and confidence from the cloud's fields.
  EXPECT_EQ(f.distance[0], static_cast<std::uint16_t>(std::lround(0.5 / drivers::nonAmbiguousRange(1) * 65535)));
  EXPECT_EQ(f.distance[5], 0);
  EXPECT_EQ(f.amplitude[0], 200);
  EXPECT_EQ(f.confidence[0], 65535);
  EXPECT_EQ(f.settings.integration_time, 30);  // no sidecar: the defaults
  EXPECT_EQ(camera.acquire().distance[0], 1001);
}

TEST_F(Playback, ImportedViewsPlayAtAChosenRateWithTheDefaultSettings) {
  // An imported view's sidecar (keyturn import) records no camera, and its capture time is the import's.
  for (double a : kAngles) {
    char name[64];
    std::snprintf(name, sizeof name, "/mug/m1/e30/a%.1f.json", a);
    std::ifstream in(root_ + name);
    nlohmann::json j = nlohmann::json::parse(in);
    j.erase("camera");
    j["imported_by"] = "keyturn import folders";
    std::ofstream(root_ + name) << j.dump(2);
  }
  EXPECT_EQ(errorOf([&] { recording(0); }), root_ +
                                                "/manifest.csv: imported views (their capture times are the import's) "
                                                "have no recorded rate: choose a playback rate");
  rig::PlaybackCamera camera(recording(5));
  const drivers::TofFrame f = camera.acquire();
  EXPECT_EQ(f.distance[0], 1000);  // its PNGs still read
  EXPECT_EQ(f.device, "");
  EXPECT_EQ(f.settings.integration_time, drivers::TofSettings().integration_time);
}
