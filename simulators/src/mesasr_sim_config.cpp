#include "keyturn/sim/mesasr_sim_config.h"

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>

#include "keyturn/core/durable_file.h"
#include "keyturn/core/error.h"
#include "keyturn/core/fnv1a.h"
#include "keyturn/core/json_file.h"
#include "keyturn/core/json_integer.h"

namespace fs = std::filesystem;

namespace keyturn::sim {

MesaSrSimConfig MesaSrSimConfig::fromEnvironment(const char* variable) {
  const char* p = std::getenv(variable);
  return p && *p ? fromFile(p) : MesaSrSimConfig();
}

MesaSrSimConfig MesaSrSimConfig::fromFile(const std::string& path) {
  const nlohmann::json j = readJsonFile(path, JsonShape::Object);
  MesaSrSimConfig c;
  try {
    c.mesh = j.value("mesh", c.mesh);
    c.distance = j.value("distance", c.distance);
    c.elevation = j.value("elevation", c.elevation);
    c.turntable_deg = j.value("turntable_deg", c.turntable_deg);
    c.roll = j.value("roll", c.roll);
    if (!(std::abs(c.roll) <= 90)) throw Error(path + ": roll must be within ±90°");
    c.scale = j.value("scale", c.scale);
    if (!(c.scale >= 0.1 && c.scale <= 10)) throw Error(path + ": scale must be in [0.1, 10]");
    c.world = j.value("world", c.world);
    c.serial = jsonInteger(j, "serial", c.serial, std::uint32_t{0}, std::numeric_limits<std::uint32_t>::max(), path);
    c.seed = jsonInteger(j, "seed", c.seed, std::uint64_t{0}, std::numeric_limits<std::uint64_t>::max(), path);
    c.frame_rate = j.value("frame_rate", c.frame_rate);
    c.noise_per_pose = j.value("noise_per_pose", c.noise_per_pose);
    c.unplug_file = j.value("unplug_file", c.unplug_file);
    if (!(c.frame_rate >= 0 && c.frame_rate <= 1000)) throw Error(path + ": frame_rate must be in [0, 1000]");
    if (j.contains("faults")) {
      const auto& f = j.at("faults");
      c.faults.open_fail = f.value("open_fail", false);
      const int most = std::numeric_limits<int>::max();
      c.faults.timeout_every = jsonInteger(f, "timeout_every", 0, 0, most, path + ": faults");
      c.faults.corrupt_every = jsonInteger(f, "corrupt_every", 0, 0, most, path + ": faults");
      c.faults.disconnect_after = jsonInteger(f, "disconnect_after", 0, 0, most, path + ": faults");
      c.faults.random_rate = f.value("random_rate", 0.0);
      if (!(c.faults.random_rate >= 0 && c.faults.random_rate <= 1)) throw Error(path + ": random_rate must be in [0, 1]");
    }
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw Error(path + ": bad simulator configuration: " + e.what());
  }
  const fs::path base = fs::path(path).parent_path();
  auto resolve = [&](std::string& p) {
    if (!p.empty() && p.rfind("builtin:", 0) != 0 && fs::path(p).is_relative()) p = (base / p).string();
  };
  resolve(c.mesh);
  resolve(c.world);
  resolve(c.unplug_file);
  return c;
}

void MesaSrSimConfig::save(const std::string& path) const {
  nlohmann::json j = {{"mesh", mesh},       {"distance", distance}, {"elevation", elevation},
                      {"turntable_deg", turntable_deg}, {"roll", roll}, {"scale", scale}, {"serial", serial}, {"seed", seed},
                      {"frame_rate", frame_rate}, {"noise_per_pose", noise_per_pose},
                      {"faults", {{"open_fail", faults.open_fail}, {"timeout_every", faults.timeout_every},
                                  {"corrupt_every", faults.corrupt_every},
                                  {"disconnect_after", faults.disconnect_after},
                                  {"random_rate", faults.random_rate}}}};
  if (!world.empty()) j["world"] = world;
  if (!unplug_file.empty()) j["unplug_file"] = unplug_file;
  writeFileDurably(path, j.dump(2) + "\n");  // the simulator re-reads it on every open
}

double readWorldTurntable(const std::string& path, double fallback) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return fallback;
  try {
    return readJsonFile(path).value("turntable_deg", fallback);
  } catch (const std::exception&) {
    return fallback;  // a writer mid-rename never leaves a torn file; anything else keeps the last pose
  }
}

void writeWorldTurntable(const std::string& path, double degrees) {
  // Rewritten at every turntable step: renamed into place (never torn) but not synced.
  const std::string tmp = path + ".tmp";
  std::ofstream out(tmp);
  out << nlohmann::json{{"turntable_deg", degrees}}.dump() << "\n";
  out.close();
  if (!out) throw Error(path + ": cannot write world state");
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) throw Error(path + ": cannot write world state: " + ec.message());
}

std::uint64_t MesaSrSimConfig::poseNoiseSeed(double turntable_deg) const {
  std::string bits(sizeof turntable_deg, '\0');
  std::memcpy(bits.data(), &turntable_deg, bits.size());
  return fnv1a(bits, seed * 1000003ULL);
}

}  // namespace keyturn::sim
