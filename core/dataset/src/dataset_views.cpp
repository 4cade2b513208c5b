#include "keyturn/dataset/dataset_views.h"

#include <filesystem>

#include "keyturn/core/error.h"
#include "keyturn/dataset/dataset.h"
#include "keyturn/dataset/dataset_layout.h"

namespace keyturn::dataset {

namespace fs = std::filesystem;

bool isDataset(const std::string& path) { return fs::is_regular_file(manifestPath(path)); }

std::vector<LabelledView> datasetViews(const std::string& root, std::vector<std::string>* skipped,
                                       std::vector<ViewRecord>* records) {
  if (!isDataset(root))
    throw Error(root + ": not a keyturn dataset (no manifest.csv)");
  std::vector<LabelledView> out;
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

}  // namespace keyturn::dataset
