// The rig's jobs behind keyturn simulate, capture and calibrate-axis: a dataset
// generated on the simulated rig (and resumed), the devices of a capture opened
// by name, a failed capture's empty folder removed, a sequence that is no
// sphere target's refused.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>

#include "keyturn/core/error.h"
#include "keyturn/rig/captured_views.h"
#include "keyturn/rig/axis_calibration_run.h"
#include "keyturn/rig/capture_rig.h"
#include "keyturn/rig/dataset_simulation.h"
#include "keyturn/dataset/sidecars.h"
#include "support/error_of.h"
#include "support/scratch_path.h"

namespace fs = std::filesystem;
using namespace keyturn;
using keyturn::test::errorOf;

namespace {

rig::DatasetSimulation mugAt(const fs::path& out) {
  rig::DatasetSimulation s;
  s.out = out.string();
  s.objects = {{"mug", "builtin", "builtin:mug"}};
  s.elevations = {30, 45};
  s.step_deg = 120;
  return s;
}

}  // namespace

TEST(DatasetSimulation, WritesEveryViewOnceAndResumes) {
  const keyturn::test::ScratchFolder scratch("rig_sim");
  const fs::path out = scratch.path / "resume";
  const rig::DatasetSimulation s = mugAt(out);
  EXPECT_EQ(s.views(), 6u);  // 1 object × 2 elevations × 3 angles
  std::size_t told = 0;
  const rig::CaptureReport first = rig::simulateDataset(s, [&] { ++told; });
  EXPECT_EQ(first.written, 6u);
  EXPECT_EQ(told, 6u);
  const dataset::VerifyReport v = dataset::Dataset::verify(out.string());
  EXPECT_TRUE(v.ok());
  EXPECT_EQ(v.views, 6u);
  const auto rows = dataset::Dataset::readManifest(out.string());
  ASSERT_EQ(rows.size(), 6u);
  EXPECT_EQ(rows.back().key.elevation, "45");
  const rig::CaptureReport again = rig::simulateDataset(s);
  EXPECT_EQ(again.written, 0u);
  EXPECT_EQ(again.skipped, 6u);
  fs::remove_all(out);
}

// The training-side twin (simulate --jitter-*): each view its own elevation, roll, distance and
// integration time, drawn from its identity alone, under the nominal view's label.
TEST(DatasetSimulation, JitterGivesEachViewItsOwnCameraUnderItsNominalLabel) {
  const keyturn::test::ScratchFolder scratch("rig_sim");
  const fs::path out = scratch.path / "jitter";
  rig::DatasetSimulation s = mugAt(out);
  s.elevations = {30};
  s.jitter.distance = 0.2;
  s.jitter.elevation_deg = 5;
  s.jitter.tilt_deg = 4;
  s.jitter.scale = 0.2;
  s.jitter.integration_min = 15;
  s.jitter.integration_max = 60;
  const dataset::ViewKey first{"mug", "builtin", "30", 0};
  const rig::JitteredView d = rig::drawJitter(s.jitter, s.seed, first, 30);
  EXPECT_EQ(rig::drawJitter(s.jitter, s.seed, first, 30).roll_deg, d.roll_deg) << "a view's draw is its own";
  EXPECT_NE(rig::drawJitter(s.jitter, s.seed + 1, first, 30).roll_deg, d.roll_deg);
  std::size_t told = 0;
  EXPECT_EQ(rig::simulateDataset(s, [&] { ++told; }).written, 3u);
  EXPECT_EQ(told, 3u);
  const auto rows = dataset::Dataset::readManifest(out.string());
  ASSERT_EQ(rows.size(), 3u);
  std::set<double> elevations;
  std::set<int> integrations;
  for (const auto& r : rows) {
    EXPECT_EQ(r.key.elevation, "30");
    EXPECT_GE(r.elevation_deg, 25.0);
    EXPECT_LE(r.elevation_deg, 35.0);
    EXPECT_NEAR(r.elevation_deg, rig::drawJitter(s.jitter, s.seed, r.key, 30).elevation_deg, 1e-3);
    elevations.insert(r.elevation_deg);
    const rig::ViewCamera cam = rig::readViewCamera((out / r.sidecar()).string());
    EXPECT_EQ(cam.settings.integration_time, rig::drawJitter(s.jitter, s.seed, r.key, 30).integration);
    integrations.insert(cam.settings.integration_time);
    // The pose is the jittered camera's: its roll tilts the table's normal out of the image's
    // vertical plane (x = 0) by sin(roll) of its length.
    const auto pose = dataset::readViewTransform((out / r.sidecar()).string());
    ASSERT_TRUE(pose.has_value());
    const Eigen::Vector3d up_in_camera = pose->topLeftCorner<3, 3>() * Eigen::Vector3d::UnitZ();
    const double roll = rig::drawJitter(s.jitter, s.seed, r.key, 30).roll_deg;
    EXPECT_NEAR(-up_in_camera.x() / std::hypot(up_in_camera.x(), up_in_camera.y()), std::sin(roll * M_PI / 180), 1e-6);
  }
  EXPECT_EQ(elevations.size(), 3u);
  EXPECT_GE(integrations.size(), 2u);
  EXPECT_TRUE(dataset::Dataset::verify(out.string()).ok());
  EXPECT_EQ(rig::simulateDataset(s).skipped, 3u) << "a jittered dataset resumes like any other";
  s.jitter.elevation_deg = 30;
  EXPECT_EQ(errorOf([&] { rig::simulateDataset(s); }), "jitter: the elevation must be within 0–20°");
  fs::remove_all(out);
}

TEST(DatasetSimulation, AMissingMeshIsNamedWithItsObject) {
  const keyturn::test::ScratchFolder scratch("rig_sim");
  rig::DatasetSimulation s = mugAt(scratch.path / "mesh");
  s.objects = {{"cup", "blue", "/nonexistent/cup.ply"}};
  EXPECT_EQ(errorOf([&] { s.checkMeshes("objects.csv"); }), "objects.csv: cup/blue: no mesh at /nonexistent/cup.ply");
}

TEST(CaptureRig, OpensTheSimulatedRigAndRefusesASimulatedTableWithARealCamera) {
  const keyturn::test::ScratchFolder scratch("rig_sim");
  const fs::path dir = scratch.path / "devices";
  rig::CaptureDevices d;
  d.sim.dir = (dir / ".sim").string();
  rig::CaptureRig simulated(d);
  ASSERT_NE(simulated.simulatedTurntable(), nullptr);
  EXPECT_TRUE(simulated.cameraFromTurntable().has_value());
  EXPECT_EQ(simulated.camera().acquire().cloud.width, 176u);  // an SR4000 frame
  d.camera = rig::CameraSpec::parse("usb");
  EXPECT_EQ(errorOf([&] { rig::CaptureRig real(d); }),
            "the simulated turntable needs the simulated SR4000 (sim) or the simulated OpenNI2 camera (openni2): the "
            "simulated table and camera share one world");
  d.camera = rig::CameraSpec::parse("sim:" + (dir / "camera.json").string());
  EXPECT_EQ(errorOf([&] { rig::CaptureRig configured(d); }),
            "camera 'sim:" + (dir / "camera.json").string() +
                "': a capture writes its simulated camera's configuration itself (mesh, distance, seed); give sim");
  fs::remove_all(dir);
}

TEST(Dataset, AFolderWithoutViewsIsRemovedOneWithViewsKept) {
  const keyturn::test::ScratchFolder scratch("rig_sim");
  const fs::path empty = scratch.path / "empty";
  { dataset::Dataset d(empty.string()); }  // dataset.json and an empty manifest, as a failed capture leaves them
  ASSERT_TRUE(fs::exists(empty));
  dataset::removeDatasetWithoutViews(empty.string());
  EXPECT_FALSE(fs::exists(empty));
  const fs::path full = scratch.path / "full";
  rig::DatasetSimulation s = mugAt(full);
  s.elevations = {30};
  rig::simulateDataset(s);
  dataset::removeDatasetWithoutViews(full.string());
  EXPECT_EQ(dataset::Dataset::readManifest(full.string()).size(), 3u);
  fs::remove_all(full);
  // A user's folder with files of its own, or a manifest keyturn did not write, is never removed.
  const fs::path theirs = scratch.path / "theirs";
  { dataset::Dataset d(theirs.string()); }
  std::ofstream(theirs / "notes.txt") << "mine";
  dataset::removeDatasetWithoutViews(theirs.string());
  EXPECT_TRUE(fs::exists(theirs / "notes.txt"));
  fs::remove(theirs / "notes.txt");
  std::ofstream(theirs / "manifest.csv", std::ios::trunc) << "id;label\n1;mug\n";
  dataset::removeDatasetWithoutViews(theirs.string());
  EXPECT_TRUE(fs::exists(theirs / "manifest.csv"));
  fs::remove_all(theirs);
}

TEST(AxisCalibrationRun, TooFewViewsAndAnObjectThatIsNoTargetAreRefused) {
  const keyturn::test::ScratchFolder scratch("rig_sim");
  const fs::path out = scratch.path / "axis";
  rig::DatasetSimulation s = mugAt(out);
  s.elevations = {30};
  rig::simulateDataset(s);
  rig::AxisSequence q{out.string(), "mug", "builtin", "45"};
  EXPECT_EQ(errorOf([&] { rig::calibrateAxisFromDataset(q, {}, {}); }),
            out.string() + ": axis calibration needs at least 3 views, found 0");
  q.elevation = "30";
  std::vector<std::size_t> progress;
  const std::string msg = errorOf([&] {
    rig::calibrateAxisFromDataset(q, {}, [&](std::size_t done, std::size_t views) {
      EXPECT_EQ(views, 3u);
      progress.push_back(done);
    });
  });
  EXPECT_EQ(progress, (std::vector<std::size_t>{0, 1, 2, 3}));
  // The mug is no ball standing off the axis: refused rather than written.
  EXPECT_EQ(msg.rfind(out.string() + ": ", 0), 0u) << msg;
  EXPECT_TRUE(msg.find("not a sphere-target sequence") != std::string::npos ||
              msg.find("the sphere target was found in only") != std::string::npos)
      << msg;
  fs::remove_all(out);
}
