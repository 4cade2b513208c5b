#pragma once
// A dataset's views as the learning tools describe them: one labelled view per
// manifest row that lists a point cloud, in manifest order.
#include <string>
#include <vector>

#include "keyturn/core/depth_image.h"
#include "keyturn/dataset/dataset.h"

namespace keyturn::dataset {

// One view to describe: its file and its labels (a dataset's view, or a loose file given as one).
struct LabelledView {
  std::string id;    // the row id: the view's stem relative to the dataset root (or the file for loose views)
  std::string path;  // the PCD/PLY file, or a depth image
  std::string cls, instance, elevation;
  DepthImageOptions depth;  // how a depth-image view is read (loadCloud)
};

// Throws keyturn::Error for a folder without a manifest or without views. Malformed manifest
// rows are skipped and, when `skipped` is given, described there; `records`, when given,
// receives each view's manifest row (parallel to the result).
std::vector<LabelledView> datasetViews(const std::string& root, std::vector<std::string>* skipped = nullptr,
                                       std::vector<ViewRecord>* records = nullptr);

// A keyturn dataset folder: one holding manifest.csv.
bool isDataset(const std::string& path);

}  // namespace keyturn::dataset
