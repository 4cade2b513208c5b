// OpenNI2 recordings (.oni) as `--camera playback:FILE.oni` opens them: keyturn's check of the
// container (drivers/oni_recording_check.h), then, for a recording it lets through, OpenNI2's own
// player (Debian's libOniFile behind keyturn's guard, from keyturn's OpenNI2 folder) opening it
// and decoding every frame of its depth and colour streams, as drivers/src/openni2_camera.cpp
// drives it. Only keyturn::Error may come out of the check, and the player must never crash on a
// recording the check passed. The player is driven here through OpenNI2's API rather than through
// OpenNi2Camera so that the fuzzer needs no more than the check and OpenNI2 (OpenNi2Camera's own
// frame-size checks are the drivers tests'). Seeds: tests/fuzz/oni_seed.py.
#include <OpenNI.h>

#include <cstdlib>

#include "fuzz_file.h"
#include "keyturn/core/error.h"
#include "keyturn/drivers/oni_recording_check.h"

namespace {

void play(const std::string& path) {
  using namespace openni;
  Device device;
  if (device.open(path.c_str()) != STATUS_OK) return;
  VideoStream depth, colour;
  if (depth.create(device, SENSOR_DEPTH) == STATUS_OK) {
    const bool has_colour = device.hasSensor(SENSOR_COLOR) && colour.create(device, SENSOR_COLOR) == STATUS_OK;
    PlaybackControl* playback = device.getPlaybackControl();
    playback->setRepeatEnabled(false);
    playback->setSpeed(0);  // no waiting between frames
    const int frames[2] = {playback->getNumberOfFrames(depth), has_colour ? playback->getNumberOfFrames(colour) : 0};
    VideoStream* streams[2] = {&depth, &colour};
    if (depth.start() == STATUS_OK && (!has_colour || colour.start() == STATUS_OK)) {
      int read[2] = {0, 0};
      // Every frame to the end; one the player could not decode never comes (300 ms).
      while (read[0] < frames[0] || read[1] < frames[1]) {
        int which = -1;
        if (OpenNI::waitForAnyStream(streams, has_colour ? 2 : 1, &which, 300) != STATUS_OK) break;
        VideoFrameRef f;
        if (streams[which]->readFrame(&f) != STATUS_OK) break;
        ++read[which];
      }
    }
    if (has_colour) colour.stop(), colour.destroy();
    depth.stop();
    depth.destroy();
  }
  device.close();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const bool started = [] {
    if (openni::OpenNI::initialize() != openni::STATUS_OK) std::abort();
    return true;
  }();
  (void)started;
  const std::string path = keyturn::fuzz::writeInput(data, size, "take.oni");
  try {
    (void)keyturn::drivers::checkOniRecording(path);
  } catch (const keyturn::Error&) {
    return 0;
  }
  play(path);
  return 0;
}
