// The simulated OpenNI2 driver through the real libOpenNI2's C++ API, as any
// OpenNI2 program sees it (this program's RUNPATH picks the simulated camera's
// libOpenNI2 folder; see tests/openni2/CMakeLists.txt).
#include <OpenNI.h>
#include <PS1080.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "sim_properties.h"
#include "support/scratch_path.h"

namespace fs = std::filesystem;
using namespace openni;

namespace {

class OpenNI2Sim : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_EQ(OpenNI::initialize(), STATUS_OK) << OpenNI::getExtendedError();
  }
  void TearDown() override { OpenNI::shutdown(); }
  // A configuration file (MesaSrSimConfig's JSON) and the URI that names it.
  std::string uri(const std::string& json, const std::string& name = "sim.json") {
    return "keyturn-sim://" + keyturn::test::writeText(dir_ / name, json);
  }
  const keyturn::test::ScratchFolder scratch_{"openni2_sim"};
  const fs::path& dir_ = scratch_.made();
};

std::vector<OniDepthPixel> pixels(const VideoFrameRef& f) {
  const auto* p = static_cast<const OniDepthPixel*>(f.getData());
  return std::vector<OniDepthPixel>(p, p + f.getWidth() * f.getHeight());
}

int middle(const VideoFrameRef& f) { return pixels(f)[240 * 640 + 320]; }

// One of the simulated device's own int properties (sim_properties.h), or -1.
int property(Device& d, int id) {
  int value = -1, size = sizeof value;
  return d.getProperty(id, &value, &size) == STATUS_OK ? value : -1;
}

bool waitFrame(VideoStream& s, int timeout_ms) {
  VideoStream* streams[] = {&s};
  int ready = -1;
  return OpenNI::waitForAnyStream(streams, 1, &ready, timeout_ms) == STATUS_OK;
}

}  // namespace

TEST_F(OpenNI2Sim, EnumeratesTheDefaultDevice) {
  Array<DeviceInfo> devices;
  OpenNI::enumerateDevices(&devices);
  ASSERT_EQ(devices.getSize(), 1);
  EXPECT_STREQ(devices[0].getUri(), "keyturn-sim://default");
  EXPECT_STREQ(devices[0].getVendor(), "keyturn");
  Device d;
  ASSERT_EQ(d.open(ANY_DEVICE), STATUS_OK) << OpenNI::getExtendedError();
  EXPECT_TRUE(d.hasSensor(SENSOR_DEPTH));
  EXPECT_TRUE(d.hasSensor(SENSOR_COLOR));
  EXPECT_TRUE(d.hasSensor(SENSOR_IR));
}

// keyturn passes its configuration in the URI; the turntable angle it names turns the mug
// (its handle faces the camera at 270°, 14 mm nearer than the body).
TEST_F(OpenNI2Sim, AUriNamesTheConfiguration) {
  auto middleDepth = [&](const std::string& u) {
    Device d;
    EXPECT_EQ(d.open(u.c_str()), STATUS_OK) << OpenNI::getExtendedError();
    VideoStream s;
    s.create(d, SENSOR_DEPTH);
    s.start();
    VideoFrameRef f;
    EXPECT_EQ(s.readFrame(&f), STATUS_OK);
    return middle(f);
  };
  const int body = middleDepth(uri(R"({"distance": 0.7, "turntable_deg": 0, "seed": 2})", "body.json"));
  const int handle = middleDepth(uri(R"({"distance": 0.7, "turntable_deg": 270, "seed": 2})", "handle.json"));
  EXPECT_NEAR(body, 654, 6);
  EXPECT_NEAR(handle, 641, 6);
  const int far = middleDepth(uri(R"({"distance": 1.5, "seed": 2})", "far.json"));
  EXPECT_NEAR(far, 1500 - 40, 25);  // the mug's front wall, one radius nearer than its axis
}

TEST_F(OpenNI2Sim, ABadConfigurationIsRefusedNamingTheFile) {
  Device d;
  const std::string missing = (dir_ / "missing.json").string();
  EXPECT_NE(d.open(("keyturn-sim://" + missing).c_str()), STATUS_OK);
  EXPECT_NE(std::string(OpenNI::getExtendedError()).find(missing + ": cannot read (No such file or directory)"), std::string::npos)
      << OpenNI::getExtendedError();
  EXPECT_NE(d.open(uri(R"({"scale": 50})").c_str()), STATUS_OK);
  EXPECT_NE(std::string(OpenNI::getExtendedError()).find("scale must be in"), std::string::npos);
  EXPECT_NE(d.open("keyturn-sim://elsewhere"), STATUS_OK);  // not a path
}

TEST_F(OpenNI2Sim, StreamsDescribeAKinectClassCamera) {
  Device d;
  ASSERT_EQ(d.open(uri(R"({"serial": 31337})").c_str()), STATUS_OK);
  char serial[64] = {};
  int size = sizeof serial;
  ASSERT_EQ(d.getProperty(ONI_DEVICE_PROPERTY_SERIAL_NUMBER, serial, &size), STATUS_OK);
  EXPECT_STREQ(serial, "31337");

  VideoStream depth, colour, ir;
  ASSERT_EQ(depth.create(d, SENSOR_DEPTH), STATUS_OK);
  ASSERT_EQ(colour.create(d, SENSOR_COLOR), STATUS_OK);
  ASSERT_EQ(ir.create(d, SENSOR_IR), STATUS_OK);
  // The focal length OpenNI2 programs (PCL's grabber among them) recover from the fields of view.
  EXPECT_NEAR(320.0 / std::tan(depth.getHorizontalFieldOfView() / 2), 580.0, 0.05);
  EXPECT_NEAR(240.0 / std::tan(depth.getVerticalFieldOfView() / 2), 580.0, 0.05);
  EXPECT_EQ(depth.getMaxPixelValue(), 4500);
  double baseline_cm = 0;  // PrimeSense's property, which PCL's grabber reads for disparity images
  ASSERT_EQ(depth.getProperty(XN_STREAM_PROPERTY_EMITTER_DCMOS_DISTANCE, &baseline_cm), STATUS_OK);
  EXPECT_DOUBLE_EQ(baseline_cm, 7.5);
  EXPECT_EQ(depth.getMinPixelValue(), 0);
  EXPECT_FALSE(depth.getMirroringEnabled());
  EXPECT_NE(depth.setMirroringEnabled(true), STATUS_OK);
  EXPECT_EQ(depth.setMirroringEnabled(false), STATUS_OK);

  const VideoMode m = depth.getVideoMode();
  EXPECT_EQ(m.getPixelFormat(), PIXEL_FORMAT_DEPTH_1_MM);
  EXPECT_EQ(m.getResolutionX(), 640);
  EXPECT_EQ(m.getResolutionY(), 480);
  EXPECT_EQ(m.getFps(), 30);
  EXPECT_EQ(d.getSensorInfo(SENSOR_DEPTH)->getSupportedVideoModes().getSize(), 2);
  EXPECT_EQ(colour.getVideoMode().getPixelFormat(), PIXEL_FORMAT_RGB888);
  EXPECT_EQ(ir.getVideoMode().getPixelFormat(), PIXEL_FORMAT_GRAY16);
  VideoMode qvga = m;
  qvga.setResolution(320, 240);
  EXPECT_NE(depth.setVideoMode(qvga), STATUS_OK);  // one resolution only
  VideoMode fine = m;
  fine.setPixelFormat(PIXEL_FORMAT_DEPTH_100_UM);
  ASSERT_EQ(depth.setVideoMode(fine), STATUS_OK);
  EXPECT_EQ(depth.getVideoMode().getPixelFormat(), PIXEL_FORMAT_DEPTH_100_UM);
  EXPECT_EQ(depth.getMaxPixelValue(), 45000);
}

TEST_F(OpenNI2Sim, DepthIn100MicrometreUnitsIsTenTimesMillimetres) {
  Device d;
  ASSERT_EQ(d.open(uri(R"({"distance": 0.7})").c_str()), STATUS_OK);
  VideoStream s;
  s.create(d, SENSOR_DEPTH);
  auto blockMean = [&](PixelFormat format) {
    VideoMode m = s.getVideoMode();
    m.setPixelFormat(format);
    EXPECT_EQ(s.setVideoMode(m), STATUS_OK);
    s.start();
    double sum = 0;
    int n = 0;
    for (int k = 0; k < 5; ++k) {
      VideoFrameRef f;
      EXPECT_EQ(s.readFrame(&f), STATUS_OK);
      EXPECT_EQ(f.getVideoMode().getPixelFormat(), format);
      const auto p = pixels(f);
      for (int v = 220; v < 260; ++v)
        for (int u = 310; u < 330; ++u)
          if (p[v * 640 + u]) sum += p[v * 640 + u], ++n;
    }
    s.stop();
    return sum / n;
  };
  const double mm = blockMean(PIXEL_FORMAT_DEPTH_1_MM), um100 = blockMean(PIXEL_FORMAT_DEPTH_100_UM);
  EXPECT_GT(mm, 600);
  EXPECT_NEAR(um100 / 10.0, mm, 1.5);
}

// 100 µm values are the lattice depths rounded finer, not millimetres times ten.
TEST_F(OpenNI2Sim, DepthIn100MicrometreUnitsIsFinerThanMillimetres) {
  Device d;
  ASSERT_EQ(d.open(uri(R"({"distance": 0.7})").c_str()), STATUS_OK);
  VideoStream s;
  s.create(d, SENSOR_DEPTH);
  VideoMode m = s.getVideoMode();
  m.setPixelFormat(PIXEL_FORMAT_DEPTH_100_UM);
  ASSERT_EQ(s.setVideoMode(m), STATUS_OK);
  s.start();
  VideoFrameRef f;
  ASSERT_EQ(s.readFrame(&f), STATUS_OK);
  int valid = 0, finer = 0;
  for (OniDepthPixel p : pixels(f)) {
    valid += p != 0;
    finer += p % 10 != 0;
  }
  EXPECT_GT(valid, 100000);
  EXPECT_GT(finer, valid / 2);
}

// Colour is rendered from the depth camera's viewpoint: registration is the identity.
TEST_F(OpenNI2Sim, DepthIsRegisteredToColour) {
  Device d;
  ASSERT_EQ(d.open(uri("{}").c_str()), STATUS_OK);
  EXPECT_TRUE(d.isImageRegistrationModeSupported(IMAGE_REGISTRATION_DEPTH_TO_COLOR));
  ASSERT_EQ(d.setImageRegistrationMode(IMAGE_REGISTRATION_DEPTH_TO_COLOR), STATUS_OK);
  EXPECT_EQ(d.getImageRegistrationMode(), IMAGE_REGISTRATION_DEPTH_TO_COLOR);
  VideoStream depth, colour;
  depth.create(d, SENSOR_DEPTH);
  colour.create(d, SENSOR_COLOR);
  int cx = -1, cy = -1;
  ASSERT_EQ(CoordinateConverter::convertDepthToColor(depth, colour, 100, 200, 650, &cx, &cy), STATUS_OK);
  EXPECT_EQ(cx, 100);
  EXPECT_EQ(cy, 200);
  // Depth and colour of one instant share a frame index (and so OpenNI's depth/colour sync works).
  ASSERT_EQ(d.setDepthColorSyncEnabled(true), STATUS_OK);
  depth.start();
  colour.start();
  VideoFrameRef df, cf;
  ASSERT_EQ(depth.readFrame(&df), STATUS_OK);
  ASSERT_EQ(colour.readFrame(&cf), STATUS_OK);
  EXPECT_LE(std::abs(df.getFrameIndex() - cf.getFrameIndex()), 1);
  // Where depth sees the mug, colour is the mug's orange.
  const auto* rgb = static_cast<const RGB888Pixel*>(cf.getData());
  EXPECT_GT(middle(df), 0);
  EXPECT_GT(rgb[240 * 640 + 320].r, rgb[240 * 640 + 320].b + 40);
}

TEST_F(OpenNI2Sim, FramesCarryIndicesAndTimestampsAtTheFrameRate) {
  Device d;
  ASSERT_EQ(d.open(uri(R"({"seed": 4})").c_str()), STATUS_OK);
  VideoStream s;
  s.create(d, SENSOR_DEPTH);
  s.start();
  std::vector<int> index;
  std::vector<std::uint64_t> stamp;
  for (int k = 0; k < 12; ++k) {
    VideoFrameRef f;
    ASSERT_EQ(s.readFrame(&f), STATUS_OK);
    index.push_back(f.getFrameIndex());
    stamp.push_back(f.getTimestamp());
  }
  for (std::size_t k = 1; k < index.size(); ++k) {
    EXPECT_GT(index[k], index[k - 1]);
    // Stamped at the frame's slot: never nearer than 1/30 s (µs); further only when the machine is slow.
    EXPECT_GE(stamp[k] - stamp[k - 1], 33300u * static_cast<unsigned>(index[k] - index[k - 1]));
  }
}

// The device builds and casts its scene when it is opened and the driver keeps it when it is closed
// (issue 51: a fresh device's first frame cast the whole scene, over 2 s under ASan on a loaded
// machine, and OpenNI2 programs' first wait timed out). Structural, not timed: the latencies are in
// docs/reliability.md and tests/bench (BM_FirstFrameOfAPreparedScene).
TEST_F(OpenNI2Sim, OpeningCastsTheSceneAndReopeningBuildsNoOther) {
  using keyturn::sim::openni2::kSceneCastsProperty;
  using keyturn::sim::openni2::kScenesBuiltProperty;
  const std::string u = uri(R"({"scale": 1.25, "distance": 0.8, "seed": 6})");
  int built = -1;
  {
    Device d;
    ASSERT_EQ(d.open(u.c_str()), STATUS_OK) << OpenNI::getExtendedError();
    built = property(d, kScenesBuiltProperty);
    EXPECT_GE(built, 1);
    EXPECT_EQ(property(d, kSceneCastsProperty), 1);  // by the open, before any stream started
    VideoStream s;
    s.create(d, SENSOR_DEPTH);
    s.start();
    for (int k = 0; k < 3; ++k) {
      VideoFrameRef f;
      ASSERT_EQ(s.readFrame(&f), STATUS_OK);
      EXPECT_GT(middle(f), 0);
    }
    EXPECT_EQ(property(d, kSceneCastsProperty), 1);  // the frames, the first too, drew noise only
  }
  Device again;
  ASSERT_EQ(again.open(u.c_str()), STATUS_OK) << OpenNI::getExtendedError();
  EXPECT_EQ(property(again, kScenesBuiltProperty), built);  // the kept scene, already cast
  EXPECT_EQ(property(again, kSceneCastsProperty), 1);
  Device other;  // another scale is another scene
  ASSERT_EQ(other.open(uri(R"({"scale": 1.5})", "other.json").c_str()), STATUS_OK) << OpenNI::getExtendedError();
  EXPECT_EQ(property(other, kScenesBuiltProperty), built + 1);
}

TEST_F(OpenNI2Sim, UnpluggingStopsFramesAndOpensFailUntilPluggedBack) {
  const std::string cable = (dir_ / "unplugged").string();
  const std::string u = uri(R"({"unplug_file": "unplugged"})");
  int built = -1;
  {
    Device d;
    ASSERT_EQ(d.open(u.c_str()), STATUS_OK);
    built = property(d, keyturn::sim::openni2::kScenesBuiltProperty);
    VideoStream s;
    s.create(d, SENSOR_DEPTH);
    s.start();
    ASSERT_TRUE(waitFrame(s, 2000));
    std::ofstream(cable).put('x');
    int late = 0;
    while (waitFrame(s, 500)) {  // at most a frame already on its way
      VideoFrameRef f;
      s.readFrame(&f);
      ASSERT_LT(++late, 3);
    }
  }
  // Closed, it cannot be opened again while unplugged; plugged back in, it can.
  Device again;
  EXPECT_NE(again.open(u.c_str()), STATUS_OK);
  EXPECT_NE(std::string(OpenNI::getExtendedError()).find("unplugged"), std::string::npos);
  fs::remove(cable);
  ASSERT_EQ(again.open(u.c_str()), STATUS_OK) << OpenNI::getExtendedError();
  // Plugged back, the device has its scene as it was: no new build or cast before its first frame.
  EXPECT_EQ(property(again, keyturn::sim::openni2::kScenesBuiltProperty), built);
  EXPECT_EQ(property(again, keyturn::sim::openni2::kSceneCastsProperty), 1);
  VideoStream s;
  s.create(again, SENSOR_DEPTH);
  s.start();
  EXPECT_TRUE(waitFrame(s, 2000));
}

TEST_F(OpenNI2Sim, AnOniRecordingPlaysBackTheSameFrames) {
  const std::string oni = (dir_ / "take.oni").string();
  std::map<int, std::vector<OniDepthPixel>> live;
  {
    Device d;
    ASSERT_EQ(d.open(uri(R"({"seed": 8, "turntable_deg": 270})").c_str()), STATUS_OK);
    VideoStream s;
    s.create(d, SENSOR_DEPTH);
    Recorder rec;
    ASSERT_EQ(rec.create(oni.c_str()), STATUS_OK) << OpenNI::getExtendedError();
    ASSERT_EQ(rec.attach(s, false), STATUS_OK) << OpenNI::getExtendedError();  // lossless
    s.start();
    ASSERT_EQ(rec.start(), STATUS_OK);
    for (int k = 0; k < 10; ++k) {
      VideoFrameRef f;
      ASSERT_EQ(s.readFrame(&f), STATUS_OK);
      live[f.getFrameIndex()] = pixels(f);
    }
    rec.stop();
    s.stop();
  }
  Device file;
  ASSERT_EQ(file.open(oni.c_str()), STATUS_OK) << OpenNI::getExtendedError();
  ASSERT_NE(file.getPlaybackControl(), nullptr);
  file.getPlaybackControl()->setRepeatEnabled(false);
  VideoStream s;
  ASSERT_EQ(s.create(file, SENSOR_DEPTH), STATUS_OK);
  const int recorded = file.getPlaybackControl()->getNumberOfFrames(s);
  EXPECT_GE(recorded, 8);
  s.start();
  int matched = 0, read = 0;
  for (; read < recorded; ++read) {
    VideoFrameRef f;
    if (!waitFrame(s, 3000) || s.readFrame(&f) != STATUS_OK) break;
    EXPECT_EQ(f.getWidth(), 640);
    const auto it = live.find(f.getFrameIndex());
    if (it == live.end()) continue;  // recorded, but not among the frames read live
    EXPECT_EQ(it->second, pixels(f)) << "frame " << f.getFrameIndex();
    ++matched;
  }
  std::printf("%d frames recorded, %d played back, %d compared with the live frames\n", recorded, read, matched);
  EXPECT_GE(matched, 5);
}

// Playback streams that come and go while another stream of the device plays on (a viewer turning
// colour on and off). Debian's recording driver (libOniFile, OpenNI2 2.2) walks its stream list on its
// player thread without a lock, while destroying a stream took it out of that list and freed it: the
// player thread then read a freed list node and crashed (issue 52: 1 run in ~150 of
// AnOniRecordingPlaysBackTheSameFrames, at its end). keyturn's drivers folder holds libOniFile behind
// a guard (libKeyturnOniFile, simulators/openni2_sim/oni_file_guard.cpp).
class OniPlayback : public OpenNI2Sim {
 protected:
  // A recording of depth and colour from the simulated camera.
  std::string record() {
    const std::string oni = (dir_ / "take.oni").string();
    Device d;
    EXPECT_EQ(d.open(uri(R"({"seed": 3})").c_str()), STATUS_OK);
    VideoStream depth, colour;
    EXPECT_EQ(depth.create(d, SENSOR_DEPTH), STATUS_OK);
    EXPECT_EQ(colour.create(d, SENSOR_COLOR), STATUS_OK);
    Recorder rec;
    EXPECT_EQ(rec.create(oni.c_str()), STATUS_OK) << OpenNI::getExtendedError();
    EXPECT_EQ(rec.attach(depth, false), STATUS_OK);
    EXPECT_EQ(rec.attach(colour, true), STATUS_OK);
    depth.start();
    colour.start();
    EXPECT_EQ(rec.start(), STATUS_OK);
    for (int k = 0; k < 5; ++k) {
      VideoFrameRef f;
      EXPECT_EQ(depth.readFrame(&f), STATUS_OK);
    }
    rec.stop();
    // The streams stop before the recorder goes: libOpenNI2 2.2's Recorder destructor locks its streams
    // list and then each stream's recorders, a frame being delivered the other way round (deadlocked
    // here once in 11 runs of this file when the streams still ran).
    depth.stop();
    colour.stop();
    return oni;
  }
};

// Colour destroyed while its frames arrive: the frame being delivered is delivered, then no more.
TEST_F(OniPlayback, AStreamDestroyedWhileItsFramesArrive) {
  const std::string oni = record();
  Device file;
  ASSERT_EQ(file.open(oni.c_str()), STATUS_OK) << OpenNI::getExtendedError();
  ASSERT_NE(file.getPlaybackControl(), nullptr);
  file.getPlaybackControl()->setSpeed(0);  // as fast as it reads, over and over
  for (int k = 0; k < 100; ++k) {
    VideoStream depth, colour;  // colour is destroyed first
    ASSERT_EQ(colour.create(file, SENSOR_COLOR), STATUS_OK) << "round " << k;
    ASSERT_EQ(depth.create(file, SENSOR_DEPTH), STATUS_OK) << "round " << k;
    ASSERT_EQ(colour.start(), STATUS_OK);
    ASSERT_EQ(depth.start(), STATUS_OK);
    ASSERT_TRUE(waitFrame(colour, 3000)) << "round " << k;
  }
}

// Colour destroyed after the recording has ended while depth is still started: the player thread
// then does nothing but walk its list (up to the first started stream, so over the colour stream,
// created first). Through libOniFile alone this crashed in every run.
TEST_F(OniPlayback, AStreamDestroyedAfterTheRecordingEnded) {
  const std::string oni = record();
  Device file;
  ASSERT_EQ(file.open(oni.c_str()), STATUS_OK) << OpenNI::getExtendedError();
  ASSERT_NE(file.getPlaybackControl(), nullptr);
  file.getPlaybackControl()->setRepeatEnabled(false);
  file.getPlaybackControl()->setSpeed(0);  // the end comes at once
  for (int k = 0; k < 100; ++k) {
    VideoStream depth, colour;  // colour is destroyed first
    ASSERT_EQ(colour.create(file, SENSOR_COLOR), STATUS_OK) << "round " << k;
    ASSERT_EQ(depth.create(file, SENSOR_DEPTH), STATUS_OK) << "round " << k;
    ASSERT_EQ(depth.start(), STATUS_OK);
    // Not a synchronisation (nothing here waits for anything): the player thread looks for a started
    // stream every 10 ms, and this lets it find depth and run, so that the destruction meets it.
    std::this_thread::sleep_for(std::chrono::milliseconds(15));
  }
}
