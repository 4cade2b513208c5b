// The OpenNI2 camera against the simulated OpenNI2 driver, loaded by Debian's real libOpenNI2
// (this test runs with the simulated driver's folder first on its library path): frames with the
// device's intrinsics and timestamps, the URI not found, reopening after the device stops
// answering, and an .oni recorded with OpenNI2's own Recorder played back frame for frame.
#include <OpenNI.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "keyturn/drivers/openni2_camera.h"
#include "support/error_of.h"
#include "support/scratch_path.h"
#include "support/under_asan.h"

namespace keyturn {
namespace {

namespace fs = std::filesystem;
using test::errorOf;

// A simulated camera's configuration (libmesasr-sim's format, read by the simulated OpenNI2 driver too).
std::string writeConfig(const fs::path& dir, const std::string& unplug_file) {
  const std::string path = (dir / "camera.json").string();
  nlohmann::json j = {{"mesh", "builtin:mug"}, {"elevation", 30}, {"seed", 7}};
  if (!unplug_file.empty()) j["unplug_file"] = unplug_file;
  std::ofstream(path) << j.dump();
  return path;
}

TEST(OpenNi2Camera, TakesFramesWithTheDevicesIntrinsicsAndTimestamps) {
  drivers::OpenNi2Camera camera(drivers::OpenNi2Options{});
  EXPECT_EQ(camera.info().uri, "keyturn-sim://default");
  // The simulated Kinect-class camera: 640 × 480, HFOV/VFOV of fx = fy = 580 px.
  EXPECT_NEAR(camera.info().intrinsics.fx, 580, 0.5);
  EXPECT_NEAR(camera.info().intrinsics.fy, 580, 0.5);
  EXPECT_DOUBLE_EQ(camera.info().intrinsics.cx, 319.5);
  EXPECT_DOUBLE_EQ(camera.info().intrinsics.cy, 239.5);
  EXPECT_EQ(camera.info().depth_mode.pixel_format, "depth 1 mm");
  EXPECT_TRUE(camera.info().has_colour);
  std::uint64_t last_stamp = 0;
  for (int i = 0; i < 3; ++i) {
    const drivers::TofFrame f = camera.acquire();
    ASSERT_EQ(f.width, 640u);
    ASSERT_EQ(f.height, 480u);
    ASSERT_EQ(f.cloud.size(), 640u * 480u);
    ASSERT_TRUE(f.depth_camera.has_value());
    EXPECT_EQ(f.sequence, static_cast<std::uint64_t>(i + 1));
    EXPECT_GT(f.depth_camera->device_timestamp_us, last_stamp);  // the device's clock moves on
    last_stamp = f.depth_camera->device_timestamp_us;
    // The mug fills part of the image; every point with a return lies in the sensor's working range
    // and on its pixel's ray.
    const std::size_t valid = f.cloud.validCount();
    EXPECT_GT(valid, 5000u);
    EXPECT_LT(valid, 640u * 480u);
    for (std::size_t p = 0; p < f.cloud.size(); ++p) {
      const Eigen::Vector3f& q = f.cloud.points[p];
      if (f.distance[p] == 0) {
        ASSERT_TRUE(std::isnan(q.z()));
        continue;
      }
      ASSERT_NEAR(q.z(), f.distance[p] * 0.001, 1e-6);
      ASSERT_GE(q.z(), 0.5f);
      ASSERT_LE(q.z(), 4.5f);
      const double u = static_cast<double>(p % 640), v = static_cast<double>(p / 640);
      ASSERT_NEAR(q.x(), (u - 319.5) * q.z() / camera.info().intrinsics.fx, 1e-4);
      ASSERT_NEAR(q.y(), (v - 239.5) * q.z() / camera.info().intrinsics.fy, 1e-4);
    }
    // Colour beside depth, registered to it by the device.
    EXPECT_EQ(f.depth_camera->colour.size(), 640u * 480u * 3u);
    EXPECT_TRUE(f.depth_camera->registered);
  }
}

TEST(OpenNi2Camera, AUriNotPresentIsNamedWithThoseThatAre) {
  drivers::OpenNi2Options o;
  o.uri = "1d27/0601@9/9";
  EXPECT_EQ(errorOf([&] { drivers::OpenNi2Camera camera(o); }),
            "OpenNI2 device '1d27/0601@9/9' not found; present: keyturn-sim://default");
}

// The folder links Debian's drivers beside the simulated one (issue 52): its DummyDevice answers the
// URI "Dummy" and is listed from then on, a device that is not keyturn's simulated camera. With both
// listed, the real one is the first device (`--camera openni2` without a URI opens it). Opened with
// OpenNI2's own API, without streams (Debian's DummyDevice crashes in its stream thread after a
// refused open), in a child process so that Dummy stays out of the other tests' device lists.
TEST(OpenNi2CameraDeathTest, TheSystemsDriversAreThereAndTheirDeviceComesFirst) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  const auto firstIsTheRealDevice = [] {
    (void)drivers::listOpenNi2Devices();  // starts OpenNI2 as keyturn does
    openni::Device dummy;
    const bool opened = dummy.open("Dummy") == openni::STATUS_OK;
    openni::Array<openni::DeviceInfo> list;
    openni::OpenNI::enumerateDevices(&list);
    std::vector<std::string> uris;
    for (int i = 0; i < list.getSize(); ++i) uris.emplace_back(list[i].getUri());
    const std::string first = drivers::firstOpenNi2Device(uris);
    std::fprintf(stderr, "Dummy %s; %zu listed, the first: %s\n", opened ? "opened" : "not opened", uris.size(), first.c_str());
    const bool ok = opened && uris.size() == 2 && first == "Dummy";
    std::_Exit(ok ? 0 : 1);  // no static destructors: OpenNI2's driver threads are still running
  };
  EXPECT_EXIT(firstIsTheRealDevice(), ::testing::ExitedWithCode(0), "");
}

// How long the reopen test waits for a frame. The simulated device casts its scene when it is opened
// and keeps it across the replug (issue 51), so a fresh device's first frame costs what later ones do;
// the bar is the device's 400 ms (12 frame periods). Under ASan with coverage every frame's noise pass
// is several times slower: at load 14-16 on 2 cores (two other ASan test processes) first frames took
// 71-505 ms and later ones up to 555 ms, and 3 of 5 runs at 400 ms failed on a later frame, so the
// sanitizer build waits 1000 ms (docs/reliability.md).
#ifdef KEYTURN_UNDER_ASAN
constexpr int kFrameTimeoutMs = 1000;
#else
constexpr int kFrameTimeoutMs = 400;
#endif

TEST(OpenNi2Camera, ReopensADeviceThatStoppedAnsweringAndGivesUpInOneLine) {
  const keyturn::test::ScratchFolder dir("openni2");
  dir.made();
  const std::string unplug = (dir.path / "unplugged").string();
  drivers::OpenNi2Options o;
  o.uri = "keyturn-sim://" + writeConfig(dir.path, unplug);
  o.timeout_ms = kFrameTimeoutMs;
  o.reconnect_attempts = 2;
  o.backoff_initial_ms = 10;
  std::vector<std::string> log;
  o.log = [&](const std::string& line) { log.push_back(line); };
  drivers::OpenNi2Camera camera(o);
  EXPECT_GT(camera.acquire().cloud.validCount(), 0u);
  log.clear();  // at a heavy load one frame (any, not only the first) may come late and be waited for again

  std::ofstream(unplug) << "cable out\n";  // frames stop; reopening fails while it is out
  // A frame delivered before the cable came out may still be read; the next one is not coming.
  std::string lost;
  for (int i = 0; i < 3 && lost.empty(); ++i) lost = errorOf([&] { camera.acquire(); });
  EXPECT_EQ(lost.rfind("OpenNI2 device " + o.uri + ": giving up after 2 reopen attempts: ", 0), 0u) << lost;
  ASSERT_EQ(log.size(), 2u);
  EXPECT_NE(log[0].find("no depth frame within " + std::to_string(kFrameTimeoutMs) +
                        " ms; reopening in 10 ms (attempt 1 of 2)"),
            std::string::npos)
      << log[0];

  fs::remove(unplug);  // plugged in again: the next acquire reopens it
  EXPECT_GT(camera.acquire().cloud.validCount(), 0u);
  EXPECT_GE(camera.reconnects(), 1);
}

TEST(OpenNi2Recordings, AnOniRecordedWithOpenNi2sRecorderPlaysBackTheSameFrames) {
  const keyturn::test::ScratchFolder dir("openni2");
  dir.made();
  const std::string oni = (dir.path / "take.oni").string();
  // Record with OpenNI2's own Recorder (as NiViewer or any OpenNI2 program would), keeping what the
  // stream delivered, by the device's timestamp.
  std::map<std::uint64_t, std::vector<std::uint16_t>> live;
  {
    ASSERT_EQ(openni::OpenNI::initialize(), openni::STATUS_OK);
    openni::Device device;
    ASSERT_EQ(device.open(openni::ANY_DEVICE), openni::STATUS_OK) << openni::OpenNI::getExtendedError();
    openni::VideoStream depth;
    ASSERT_EQ(depth.create(device, openni::SENSOR_DEPTH), openni::STATUS_OK);
    openni::Recorder recorder;
    ASSERT_EQ(recorder.create(oni.c_str()), openni::STATUS_OK);
    ASSERT_EQ(recorder.attach(depth), openni::STATUS_OK);
    ASSERT_EQ(depth.start(), openni::STATUS_OK);
    ASSERT_EQ(recorder.start(), openni::STATUS_OK);
    for (int i = 0; i < 8; ++i) {
      openni::VideoFrameRef f;
      ASSERT_EQ(depth.readFrame(&f), openni::STATUS_OK);
      const auto* d = static_cast<const std::uint16_t*>(f.getData());
      live[f.getTimestamp()].assign(d, d + f.getWidth() * f.getHeight());
    }
    recorder.stop();
    recorder.destroy();
    depth.stop();
    depth.destroy();
    device.close();
  }
  drivers::OpenNi2Options o;
  o.oni_file = oni;
  o.loop = false;
  drivers::OpenNi2Camera camera(o);
  EXPECT_EQ(camera.info().uri, oni);
  std::map<std::uint64_t, std::vector<std::uint16_t>> played;
  for (;;) {
    drivers::TofFrame f;
    try {
      f = camera.acquire();
    } catch (const drivers::EndOfRecording& e) {
      EXPECT_EQ(std::string(e.what()).rfind(oni + ": end of the recording after its ", 0), 0u) << e.what();
      break;
    }
    ASSERT_LT(played.size(), 1000u);
    EXPECT_EQ(f.width, 640u);
    played[f.depth_camera->device_timestamp_us] = f.distance;
  }
  ASSERT_GE(played.size(), live.size());
  // The recorder counts time from its first frame: find the live frames' offset by the first one's
  // depth, then every frame read live is in the recording at its time, unchanged.
  std::int64_t offset = -1;
  for (const auto& [t, depth] : played)
    if (depth == live.begin()->second) {
      offset = static_cast<std::int64_t>(live.begin()->first) - static_cast<std::int64_t>(t);
      break;
    }
  ASSERT_GE(offset, 0) << "the first frame read live is not in the recording";
  for (const auto& [t, depth] : live) {
    const auto it = played.find(t - static_cast<std::uint64_t>(offset));
    ASSERT_NE(it, played.end()) << "live frame at " << t << " us";
    EXPECT_EQ(it->second, depth) << "live frame at " << t << " us";
  }
}

}  // namespace
}  // namespace keyturn
