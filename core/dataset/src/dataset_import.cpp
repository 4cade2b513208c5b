#include "keyturn/dataset/dataset_import.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <tuple>

#include "keyturn/core/cloud_io.h"
#include "keyturn/core/depth_image.h"
#include "keyturn/core/error.h"
#include "keyturn/dataset/dataset_layout.h"

namespace fs = std::filesystem;

namespace keyturn::dataset {
namespace {

bool isPng(const std::string& file) {
  std::string ext = fs::path(file).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext == ".png";
}

// A new folder, an empty one or a keyturn dataset (an earlier import to resume): anything else would
// leave files verify calls orphans.
void checkOut(const std::string& out) {
  std::error_code ec;
  if (!fs::exists(out, ec)) return;
  if (!fs::is_directory(out, ec)) throw Error(out + ": exists and is not a folder");
  if (fs::is_regular_file(manifestPath(out), ec)) return;
  if (!fs::is_empty(out, ec)) throw Error(out + ": exists and is neither empty nor a keyturn dataset (no manifest.csv)");
}

// "FILE: what is wrong", the file named once.
std::string fileProblem(const std::string& file, const Error& e) {
  const std::string msg = e.what();
  return msg.rfind(file, 0) == 0 ? msg : file + ": " + msg;
}

}  // namespace

std::string ImportReport::text(const ImportOptions& o) const {
  std::ostringstream s;
  for (const auto& p : problems) s << p << "\n";
  s << o.source << " → " << o.out << ": " << imported << " views imported";
  if (already) s << ", " << already << " already there";
  s << ", " << problems.size() << (problems.size() == 1 ? " problem" : " problems") << "\n";
  return s.str();
}

ImportReport importDataset(const ImportOptions& o) {
  ImportPlan plan;
  DepthImageOptions depth = o.depth;
  std::string importer = "keyturn import " + o.format;
  if (!o.categories.empty() && o.format != "bigbird")
    throw Error("a categories file is for bigbird (" + o.format + " names each view's class by its folder)");
  if (o.format == "washington") {
    plan = planWashingtonImport(o.source);
    if (!depth.intrinsics) depth.intrinsics = washingtonIntrinsics();
  } else if (o.format == "folders") {
    plan = planFoldersImport(o.source);
  } else if (o.format == "bigbird") {
    plan = planBigbirdImport(o.source, o.categories);
  } else {
    throw Error("import format '" + o.format + "': expected washington, folders or bigbird");
  }
  if (!depth.intrinsics) {
    // A depth image cannot be read without them: refused before anything is written. A PNG that is
    // no depth image (8-bit, colour, corrupt) is that file's problem, as it is with them.
    std::vector<ImportedView> usable;
    for (auto& v : plan.views) {
      if (isPng(v.file)) {
        try {
          checkDepthImage(v.file);
        } catch (const Error& e) {
          plan.problems.push_back(fileProblem(v.file, e));
          continue;
        }
        throw MissingIntrinsicsError(v.file + ": depth images need the camera's intrinsics");
      }
      usable.push_back(std::move(v));
    }
    plan.views = std::move(usable);
  }
  if (plan.views.empty()) {
    std::string why = o.source + ": no views in the " + o.format + " layout";
    if (!plan.problems.empty()) why += " (" + std::to_string(plan.problems.size()) + " files not usable, first: " + plan.problems.front() + ")";
    throw Error(why);
  }
  std::sort(plan.views.begin(), plan.views.end(), [](const ImportedView& a, const ImportedView& b) {
    return std::tie(a.key.cls, a.key.instance, a.key.elevation, a.key.commanded_deg) <
           std::tie(b.key.cls, b.key.instance, b.key.elevation, b.key.commanded_deg);
  });

  checkOut(o.out);
  Dataset ds(o.out);
  ImportReport rep;
  rep.problems = plan.problems;
  const std::size_t total = plan.views.size();
  for (std::size_t i = 0; i < total; ++i) {
    const ImportedView& v = plan.views[i];
    if (ds.has(v.key)) {
      ++rep.already;
    } else {
      try {
        const Cloud cloud = v.read ? v.read() : loadCloud(v.file, depth);
        if (cloud.validCount() == 0) throw Error(v.file + ": no valid point (every pixel without a return or masked out)");
        ViewMetadata meta;
        meta.elevation_deg = v.elevation_deg;
        meta.measured_deg = v.key.commanded_deg;
        meta.pose_source = v.angle_note;
        meta.camera_from_turntable = v.camera_from_turntable;
        ds.writeImported(v.key, meta, cloud, fs::absolute(v.file).lexically_normal().string(), importer);
        ++rep.imported;
      } catch (const Error& e) {
        rep.problems.push_back(fileProblem(v.file, e));
      }
    }
    if (o.progress) o.progress(i + 1, total);
  }
  return rep;
}

}  // namespace keyturn::dataset
