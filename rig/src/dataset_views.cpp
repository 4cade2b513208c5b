#include "keyturn/rig/dataset_views.h"

#include <filesystem>

#include "keyturn/core/error.h"
#include "keyturn/rig/dataset.h"

namespace keyturn::rig {

namespace fs = std::filesystem;

std::vector<learning::LabelledView> datasetViews(const std::string& root, std::vector<std::string>* skipped,
                                                 std::vector<ViewRecord>* records) {
  if (!fs::is_regular_file(fs::path(root) / "manifest.csv"))
    throw Error(root + ": not a keyturn dataset (no manifest.csv)");
  std::vector<learning::LabelledView> out;
  for (const auto& r : Dataset::readManifest(root, skipped)) {
    const std::string pcd = r.pcd();
    if (pcd.empty()) continue;
    out.push_back({pcd.substr(0, pcd.size() - 4), (fs::path(root) / pcd).string(), r.key.cls, r.key.instance,
                   r.key.elevation, {}});
    if (records) records->push_back(r);
  }
  if (out.empty()) throw Error(root + ": the dataset has no views");
  return out;
}

}  // namespace keyturn::rig
