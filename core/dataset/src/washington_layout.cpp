// The Washington RGB-D Object Dataset's two layouts (Lai et al., ICRA 2011): point clouds
// CATEGORY/INSTANCE/INSTANCE_VIDEO_FRAME.pcd, and the cropped images
// CATEGORY/INSTANCE/INSTANCE_VIDEO_FRAME_{crop,depthcrop,maskcrop}.png + _loc.txt.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>

#include "keyturn/core/error.h"
#include "keyturn/dataset/dataset_import.h"
#include "layout_walk.h"

namespace fs = std::filesystem;

namespace keyturn::dataset {
namespace {

struct Frame {
  int video = 0, frame = 0;
};

// "INSTANCE_V_F" → video and frame; false when the name is not of that form.
bool parseFrame(const std::string& stem, const std::string& instance, Frame& out) {
  if (stem.size() <= instance.size() + 1 || stem.compare(0, instance.size() + 1, instance + "_") != 0) return false;
  const std::string rest = stem.substr(instance.size() + 1);
  const auto us = rest.find('_');
  if (us == std::string::npos) return false;
  const std::string v = rest.substr(0, us), f = rest.substr(us + 1);
  auto digits = [](const std::string& s) {
    return !s.empty() && s.size() < 9 && std::all_of(s.begin(), s.end(), [](unsigned char c) { return std::isdigit(c); });
  };
  if (!digits(v) || !digits(f)) return false;
  out = {std::stoi(v), std::stoi(f)};
  return true;
}

bool endsWith(const std::string& s, const std::string& suffix) {
  return s.size() > suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

double elevationOfVideo(int video) { return video == 1 ? 30 : video == 2 ? 45 : video == 4 ? 60 : std::nan(""); }

}  // namespace

DepthIntrinsics washingtonIntrinsics() { return {570.3, 570.3, 319.0, 239.0}; }

ImportPlan planWashingtonImport(const std::string& source) {
  ImportPlan plan;
  struct Found {
    std::string category, instance;
    Frame frame;
    std::string pcd, depth, mask, loc;  // the files present for this frame
  };
  std::map<std::string, Found> frames;  // by CATEGORY/INSTANCE/INSTANCE_V_F
  const char* kExpected = "expected INSTANCE_VIDEO_FRAME.pcd or INSTANCE_VIDEO_FRAME_depthcrop.png";
  for (const auto& f : layoutFiles(source, plan.problems)) {
    if (f.parts.size() != 3) {
      plan.problems.push_back(f.path + ": not at CATEGORY/INSTANCE/FILE (Washington RGB-D layout)");
      continue;
    }
    const std::string& category = f.parts[0];
    const std::string& instance = f.parts[1];
    const std::string& name = f.parts[2];
    std::string stem, kind;
    for (const char* suffix : {"_depthcrop.png", "_maskcrop.png", "_loc.txt", "_crop.png", ".pcd"})
      if (endsWith(name, suffix)) {
        stem = name.substr(0, name.size() - std::string(suffix).size());
        kind = suffix;
        break;
      }
    Frame fr;
    if (kind.empty() || !parseFrame(stem, instance, fr)) {
      plan.problems.push_back(f.path + ": malformed name (" + kExpected + ", INSTANCE = its folder '" + instance + "')");
      continue;
    }
    if (kind == "_crop.png") continue;  // the colour image: keyturn describes shape only
    if (std::isnan(elevationOfVideo(fr.video))) {
      plan.problems.push_back(f.path + ": video " + std::to_string(fr.video) +
                              " (Washington's videos are 1, 2, 4: the 30°, 45°, 60° elevations)");
      continue;
    }
    Found& e = frames[category + "/" + instance + "/" + stem];
    e.category = category;
    e.instance = instance;
    e.frame = fr;
    (kind == ".pcd" ? e.pcd : kind == "_depthcrop.png" ? e.depth : kind == "_maskcrop.png" ? e.mask : e.loc) = f.path;
  }

  // The frames each video spans, for its angles.
  std::map<std::string, std::pair<int, int>> span;  // CATEGORY/INSTANCE/V → first, last frame
  for (const auto& [id, e] : frames) {
    const std::string video = e.category + "/" + e.instance + "/" + std::to_string(e.frame.video);
    auto it = span.find(video);
    if (it == span.end()) span[video] = {e.frame.frame, e.frame.frame};
    else it->second = {std::min(it->second.first, e.frame.frame), std::max(it->second.second, e.frame.frame)};
  }
  for (const auto& [id, e] : frames) {
    std::string file = e.pcd;
    if (file.empty()) {
      const std::string base = (fs::path(source) / id).string();
      std::vector<std::string> missing;
      if (e.depth.empty()) missing.push_back(base + "_depthcrop.png");
      if (e.mask.empty()) missing.push_back(base + "_maskcrop.png");
      if (e.loc.empty()) missing.push_back(base + "_loc.txt");
      if (!missing.empty()) {
        std::string line = "missing " + missing.front();
        for (std::size_t i = 1; i < missing.size(); ++i) line += " and " + missing[i];
        plan.problems.push_back(line + " (a cropped view needs its _depthcrop.png, _maskcrop.png and _loc.txt)");
        continue;
      }
      file = e.depth;
    } else if (!e.depth.empty()) {
      plan.problems.push_back(e.depth + ": the same view as " + e.pcd + " (the PCD imported)");
    }
    const auto [first, last] = span.at(e.category + "/" + e.instance + "/" + std::to_string(e.frame.video));
    ImportedView v;
    v.elevation_deg = elevationOfVideo(e.frame.video);
    v.key = {e.category, e.instance, std::to_string(static_cast<int>(v.elevation_deg)),
             360.0 * (e.frame.frame - first) / (last - first + 1)};
    v.file = file;
    v.angle_note = "none: Washington RGB-D video " + std::to_string(e.frame.video) + " frame " +
                   std::to_string(e.frame.frame) + ", angle = 360° × (frame − " + std::to_string(first) + ") / " +
                   std::to_string(last - first + 1) + " frames (one turn per video)";
    plan.views.push_back(v);
  }
  return plan;
}

}  // namespace keyturn::dataset
