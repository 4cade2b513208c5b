// Corrupt .oni recordings refused in one line before OpenNI2's libOniFile reads them
// (drivers/oni_recording_check.h): recordings of the simulated camera with 20 random bytes changed
// in their first 4 KB, which crashed keyturn inside libOniFile (issue 52; tests/data/oni-corrupt),
// and single faults written into the fuzzer's seed recording; valid recordings still play.
#include "keyturn/drivers/oni_recording_check.h"

#include <OpenNI.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "keyturn/drivers/openni2_camera.h"
#include "support/error_of.h"
#include "support/scratch_path.h"

namespace keyturn {
namespace {

namespace fs = std::filesystem;
using test::errorOf;

std::string openError(const std::string& oni) {
  return errorOf([&] {
    drivers::OpenNi2Options o;
    o.oni_file = oni;
    o.loop = false;
    drivers::OpenNi2Camera camera(o);
  });
}

TEST(OniRecordingCheck, RecordingsThatCrashedLibOniFileAreRefusedInOneLine) {
  const std::string dir = std::string(KEYTURN_TEST_DATA_DIR) + "/oni-corrupt/";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"flip0.oni", "at byte 747: property name with a byte that is not printable ASCII"},
      {"flip1.oni", "at byte 222: property name with a byte that is not printable ASCII"},
      {"flip4.oni", "at byte 358: property xnSupportedMapOutputModes of 42008 bytes, past its record"},
      {"flip5.oni", "at byte 98: property name with a byte that is not printable ASCII"},
      {"flip6.oni", "at byte 24: node name of 62982 bytes"},
  };
  for (const auto& [file, what] : cases)
    EXPECT_EQ(openError(dir + file), dir + file + ": not a readable .oni recording (" + what + ")");
}

// The fuzzer's seed: a 4 x 3 uncompressed depth stream of two frames (tests/fuzz/oni_seed.py).
std::vector<char> seed() {
  std::ifstream in(std::string(KEYTURN_ONI_SEEDS) + "/depth-4x3.oni", std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

// Where `name`'s value starts in the first property record of that name.
std::size_t valueOf(const std::vector<char>& b, const std::string& name) {
  const std::string key = name + '\0';
  const auto it = std::search(b.begin(), b.end(), key.begin(), key.end());
  EXPECT_NE(it, b.end()) << name;
  return static_cast<std::size_t>(it - b.begin()) + key.size() + 4;  // past the value's size
}

std::string write(const test::ScratchFolder& dir, const std::string& name, const std::vector<char>& b) {
  const std::string path = (dir.made() / name).string();
  std::ofstream(path, std::ios::binary).write(b.data(), static_cast<std::streamsize>(b.size()));
  return path;
}

TEST(OniRecordingCheck, TheSeedRecordingPassesAndPlaysItsFrames) {
  const std::string oni = std::string(KEYTURN_ONI_SEEDS) + "/depth-4x3.oni";
  EXPECT_EQ(drivers::checkOniRecording(oni), 2);
  EXPECT_EQ(drivers::checkOniRecording(std::string(KEYTURN_ONI_SEEDS) + "/depth-4x3-colour-jpeg.oni"), 2);
  drivers::OpenNi2Options o;
  o.oni_file = oni;
  o.loop = false;
  drivers::OpenNi2Camera camera(o);
  std::vector<std::vector<std::uint16_t>> frames;
  for (;;) {
    try {
      frames.push_back(camera.acquire().distance);
    } catch (const drivers::EndOfRecording&) {
      break;
    }
    ASSERT_LT(frames.size(), 10u);
  }
  ASSERT_EQ(frames.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k)
    for (std::size_t i = 0; i < 12; ++i) EXPECT_EQ(frames[k][i], 800 + 10 * k + i) << k << " " << i;
}

TEST(OniRecordingCheck, EachFaultIsNamedWithWhereItIs) {
  const test::ScratchFolder dir("oni-check");
  const std::vector<char> good = seed();
  ASSERT_GT(good.size(), 1000u);
  const std::string prefix = ": not a readable .oni recording (";
  auto refused = [&](const std::string& name, const std::vector<char>& b) {
    const std::string path = write(dir, name, b);
    const std::string e = openError(path);
    EXPECT_EQ(e.rfind(path + prefix, 0), 0u) << e;
    return e.substr(std::min(e.size(), path.size() + prefix.size()));
  };
  auto set32 = [](std::vector<char>& b, std::size_t at, std::uint32_t v) { std::memcpy(b.data() + at, &v, 4); };

  std::vector<char> b(good.begin(), good.begin() + 1133);  // inside the second frame's pixels
  EXPECT_EQ(refused("cut.oni", b), "at byte 1083: frame record cut short by the end of the file)");

  b = good;
  set32(b, valueOf(b, "oniRequiredFrameSize"), 30);
  EXPECT_NE(refused("size.oni", b).find("node 'Depth' of 4 x 3 pixels in 30-byte frames"), std::string::npos);

  b = good;  // a smaller image in frames of its size: each 24-byte frame no longer fits one
  set32(b, valueOf(b, "oniRequiredFrameSize"), 12);
  set32(b, valueOf(b, "xnMapOutputMode"), 2);
  EXPECT_NE(refused("mode.oni", b).find("uncompressed frame of 24 bytes, more than 12"), std::string::npos);

  b = good;
  set32(b, valueOf(b, "xnSupportedMapOutputModesCount"), 3);
  EXPECT_NE(refused("modes.oni", b).find("property xnSupportedMapOutputModes of 12 bytes for 3 modes"),
            std::string::npos);

  b = good;  // one byte past 127 in a property's name crashed libOniFile's name hash (fuzz_oni)
  b[valueOf(b, "oniRequiredFrameSize") - 4 - 11] = static_cast<char>(0x9c);
  EXPECT_EQ(refused("name.oni", b), "at byte 98: property name with a byte that is not printable ASCII)");

  b = good;
  set32(b, 20, 300);  // the header's largest node id
  EXPECT_EQ(refused("nodes.oni", b), "at byte 20: largest node id 300 (at most 255))");

  b = good;
  set32(b, 24 + 8, 2);  // the node-added record names node 2, past the header's largest (1)
  EXPECT_EQ(refused("node.oni", b), "at byte 24: node-added record of node 2 past the header's largest id 1)");
}

TEST(OniRecordingCheck, ARecordingOfTheSimulatedCameraWithColourPasses) {
  const test::ScratchFolder dir("oni-check");
  const std::string oni = (dir.made() / "colour.oni").string();
  {
    ASSERT_EQ(openni::OpenNI::initialize(), openni::STATUS_OK);
    openni::Device device;
    ASSERT_EQ(device.open(openni::ANY_DEVICE), openni::STATUS_OK) << openni::OpenNI::getExtendedError();
    openni::VideoStream depth, colour;
    ASSERT_EQ(depth.create(device, openni::SENSOR_DEPTH), openni::STATUS_OK);
    ASSERT_EQ(colour.create(device, openni::SENSOR_COLOR), openni::STATUS_OK);
    openni::Recorder recorder;
    ASSERT_EQ(recorder.create(oni.c_str()), openni::STATUS_OK);
    ASSERT_EQ(recorder.attach(depth), openni::STATUS_OK);
    ASSERT_EQ(recorder.attach(colour, true), openni::STATUS_OK);  // JPEG-compressed colour
    ASSERT_EQ(depth.start(), openni::STATUS_OK);
    ASSERT_EQ(colour.start(), openni::STATUS_OK);
    ASSERT_EQ(recorder.start(), openni::STATUS_OK);
    for (int i = 0; i < 4; ++i) {
      openni::VideoFrameRef f;
      ASSERT_EQ(depth.readFrame(&f), openni::STATUS_OK);
    }
    recorder.stop();
    recorder.destroy();
    colour.stop();
    colour.destroy();
    depth.stop();
    depth.destroy();
    device.close();
  }
  // At least the four depth frames read while recording, and colour beside them.
  EXPECT_GE(drivers::checkOniRecording(oni), 5);
  drivers::OpenNi2Options o;
  o.oni_file = oni;
  o.loop = false;
  drivers::OpenNi2Camera camera(o);
  EXPECT_TRUE(camera.info().has_colour);
  EXPECT_EQ(camera.acquire().width, 640u);
}

}  // namespace
}  // namespace keyturn
