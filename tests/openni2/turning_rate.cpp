// The simulated OpenNI2 camera's frame rate while the turntable turns (issue 52: it must keep the
// camera's 30 frames/s; each frame at a new angle is cast anew). A thread moves the simulated world
// at DEG_PER_S, written every 5 ms as the simulated turntable writes it when polled; the main thread
// reads depth, colour and IR as keyturn's camera does. Prints one JSON line: frames/s and the gaps
// between frame timestamps. A rate is the machine's: run it by hand (docs/camera.md), not as a bar.
//   openni2_turning_rate MESH DEG_PER_S SECONDS WORKDIR
#include <OpenNI.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

namespace {

using Clock = std::chrono::steady_clock;

// A client of OpenNI2 only, as a foreign program is: the files are written as keyturn's simulated
// turntable (writeWorldTurntable) and MesaSrSimConfig write them, not through them.
void writeJson(const std::string& path, const nlohmann::json& j) {
  std::ofstream(path + ".tmp") << j.dump() << "\n";
  std::filesystem::rename(path + ".tmp", path);  // as the simulated turntable: never torn
}

void writeWorld(const std::string& path, double deg) { writeJson(path, {{"turntable_deg", deg}}); }

}  // namespace

int main(int argc, char** argv) {
  if (argc != 5) {
    std::fprintf(stderr, "usage: openni2_turning_rate MESH DEG_PER_S SECONDS WORKDIR\n");
    return 2;
  }
  const std::string mesh = std::filesystem::absolute(argv[1]).string(), work = argv[4];  // the config resolves paths from its folder
  const double deg_s = std::stod(argv[2]), seconds = std::stod(argv[3]);
  std::filesystem::create_directories(work);
  const std::string world = std::filesystem::absolute(work + "/world.json").string();
  const std::string config = std::filesystem::absolute(work + "/camera.json").string();
  writeWorld(world, 0.0);
  writeJson(config, {{"mesh", mesh}, {"elevation", 30}, {"world", world}});

  if (openni::OpenNI::initialize() != openni::STATUS_OK) {
    std::fprintf(stderr, "OpenNI2: %s\n", openni::OpenNI::getExtendedError());
    return 1;
  }
  openni::Device device;
  if (device.open(("keyturn-sim://" + config).c_str()) != openni::STATUS_OK) {
    std::fprintf(stderr, "%s: %s\n", config.c_str(), openni::OpenNI::getExtendedError());
    return 1;
  }
  openni::VideoStream depth, colour, ir;
  depth.create(device, openni::SENSOR_DEPTH);
  colour.create(device, openni::SENSOR_COLOR);
  ir.create(device, openni::SENSOR_IR);
  depth.start();
  colour.start();
  ir.start();

  std::atomic<bool> stop{false};
  const auto t0 = Clock::now();
  std::thread table([&] {
    while (!stop) {
      writeWorld(world, std::fmod(deg_s * std::chrono::duration<double>(Clock::now() - t0).count(), 360.0));
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  });
  openni::VideoStream* streams[] = {&depth};
  std::vector<double> gaps_ms;
  long frames = 0;
  double last_us = -1;
  const auto start = Clock::now();
  bool timed_out = false;
  while (std::chrono::duration<double>(Clock::now() - start).count() < seconds) {
    int ready = -1;
    if (openni::OpenNI::waitForAnyStream(streams, 1, &ready, 2000) != openni::STATUS_OK) {
      timed_out = true;
      break;
    }
    openni::VideoFrameRef frame, side;
    depth.readFrame(&frame);
    colour.readFrame(&side);
    ir.readFrame(&side);
    const double us = static_cast<double>(frame.getTimestamp());
    if (last_us >= 0) gaps_ms.push_back((us - last_us) / 1e3);
    last_us = us;
    ++frames;
  }
  const double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
  stop = true;
  table.join();
  depth.destroy();
  colour.destroy();
  ir.destroy();
  device.close();
  openni::OpenNI::shutdown();
  if (timed_out || gaps_ms.empty()) {
    std::fprintf(stderr, "%s: no frame within 2 s while the table turned\n", config.c_str());
    return 1;
  }
  std::sort(gaps_ms.begin(), gaps_ms.end());
  std::printf("{\"deg_per_s\": %g, \"frames\": %ld, \"frames_per_s\": %.2f, \"gap_median_ms\": %.1f, "
              "\"gap_p95_ms\": %.1f, \"gap_max_ms\": %.1f}\n",
              deg_s, frames, frames / elapsed, gaps_ms[gaps_ms.size() / 2], gaps_ms[gaps_ms.size() * 95 / 100],
              gaps_ms.back());
  return 0;
}
