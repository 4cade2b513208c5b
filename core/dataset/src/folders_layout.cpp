// Labelled folders of views: CLASS/INSTANCE/[eLABEL/]VIEW.{pcd,ply,png}, as people sort real
// clouds by hand.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <map>

#include "keyturn/core/error.h"
#include "keyturn/core/view_files.h"
#include "keyturn/dataset/dataset_import.h"
#include "layout_walk.h"

namespace fs = std::filesystem;

namespace keyturn::dataset {
namespace {

std::string lowerExtension(const std::string& name) {
  std::string ext = fs::path(name).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

// "35.0" → 35; NaN unless the whole text is a finite number.
double numberOrNan(const std::string& s) {
  std::size_t used = 0;
  double v = std::nan("");
  try {
    v = std::stod(s, &used);
  } catch (const std::exception&) {
    return std::nan("");
  }
  return used == s.size() && std::isfinite(v) ? v : std::nan("");
}

// Names sorted as people number files: "v2" before "v10".
bool naturalLess(const std::string& a, const std::string& b) {
  std::size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    if (std::isdigit(static_cast<unsigned char>(a[i])) && std::isdigit(static_cast<unsigned char>(b[j]))) {
      std::size_t i2 = i, j2 = j;
      while (i2 < a.size() && std::isdigit(static_cast<unsigned char>(a[i2]))) ++i2;
      while (j2 < b.size() && std::isdigit(static_cast<unsigned char>(b[j2]))) ++j2;
      const std::string na = a.substr(i, i2 - i), nb = b.substr(j, j2 - j);
      const auto sa = na.find_first_not_of('0'), sb = nb.find_first_not_of('0');
      const std::string ta = sa == std::string::npos ? "" : na.substr(sa), tb = sb == std::string::npos ? "" : nb.substr(sb);
      if (ta.size() != tb.size()) return ta.size() < tb.size();
      if (ta != tb) return ta < tb;
      i = i2, j = j2;
    } else {
      if (a[i] != b[j]) return a[i] < b[j];
      ++i, ++j;
    }
  }
  return a.size() - i < b.size() - j;
}

}  // namespace

ImportPlan planFoldersImport(const std::string& source) {
  ImportPlan plan;
  struct Group {
    std::string cls, instance, label;
    double elevation_deg = std::nan("");
    std::vector<std::pair<std::string, std::string>> views;  // VIEW name, file
  };
  std::map<std::string, Group> groups;
  for (const auto& f : layoutFiles(source, plan.problems)) {
    const std::string& name = f.parts.back();
    const std::string ext = lowerExtension(name);
    if (ext == ".png" && isCompanionImage(name)) continue;  // masks and colour images beside depth images
    if (ext == ".txt" && name.size() > 8 && name.compare(name.size() - 8, 8, "_loc.txt") == 0) continue;  // crop offsets
    if (ext != ".pcd" && ext != ".ply" && ext != ".png") {
      plan.problems.push_back(f.path + ": not a view (expected .pcd, .ply or a 16-bit depth .png)");
      continue;
    }
    const bool with_elevation = f.parts.size() == 4;
    if (f.parts.size() != 3 && !with_elevation) {
      plan.problems.push_back(f.path + ": not at CLASS/INSTANCE/[eLABEL/]VIEW");
      continue;
    }
    Group g;
    g.cls = f.parts[0];
    g.instance = f.parts[1];
    g.label = "unknown";
    if (with_elevation) {
      const std::string& folder = f.parts[2];
      if (folder.size() < 2 || folder[0] != 'e') {
        plan.problems.push_back(f.path + ": the folder between INSTANCE and VIEW must be eLABEL (e.g. e30), not '" +
                                folder + "'");
        continue;
      }
      g.label = folder.substr(1);
      g.elevation_deg = numberOrNan(g.label);
    }
    const std::string view = fs::path(name).stem().string();
    Group& into = groups.emplace(g.cls + "/" + g.instance + "/" + g.label, g).first->second;
    into.views.push_back({view, f.path});
  }
  for (auto& [id, g] : groups) {
    std::sort(g.views.begin(), g.views.end(), [](const auto& a, const auto& b) { return naturalLess(a.first, b.first); });
    bool all_angles = true;
    for (const auto& [view, file] : g.views)
      all_angles = all_angles && view.size() > 1 && view[0] == 'a' && !std::isnan(numberOrNan(view.substr(1)));
    for (std::size_t i = 0; i < g.views.size(); ++i) {
      ImportedView v;
      v.elevation_deg = g.elevation_deg;
      v.file = g.views[i].second;
      const double angle = all_angles ? numberOrNan(g.views[i].first.substr(1)) : 360.0 * i / g.views.size();
      v.key = {g.cls, g.instance, g.label, angle};
      v.angle_note = all_angles ? "none: the angle is the view's name (" + g.views[i].first + ")"
                                : "none: view " + std::to_string(i + 1) + " of " + std::to_string(g.views.size()) +
                                      " in name order, spread evenly over one turn";
      plan.views.push_back(v);
    }
  }
  return plan;
}

}  // namespace keyturn::dataset
