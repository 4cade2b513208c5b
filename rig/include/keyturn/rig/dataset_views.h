#pragma once
// A dataset's views as the learning tools describe them: one labelled view per
// manifest row that lists a point cloud, in manifest order.
#include <string>
#include <vector>

#include "keyturn/learning/feature_cache.h"

namespace keyturn::rig {

struct ViewRecord;  // keyturn/rig/dataset.h

// Throws keyturn::Error for a folder without a manifest or without views. Malformed manifest
// rows are skipped and, when `skipped` is given, described there; `records`, when given,
// receives each view's manifest row (parallel to the result).
std::vector<learning::LabelledView> datasetViews(const std::string& root, std::vector<std::string>* skipped = nullptr,
                                                 std::vector<ViewRecord>* records = nullptr);

}  // namespace keyturn::rig
