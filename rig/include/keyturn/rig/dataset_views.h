#pragma once
// A dataset's views as the feature cache takes them (learning/feature_cache.h):
// row id (the view's PCD path relative to the root, without .pcd), file and
// labels, in manifest order.
#include <functional>
#include <string>
#include <vector>

#include "keyturn/learning/feature_cache.h"

namespace keyturn::rig {

// skipped: told of each manifest row that was skipped. Throws keyturn::Error for a folder without
// a manifest ("not a keyturn dataset") or without views.
std::vector<learning::LabelledView> datasetViews(const std::string& root,
                                                 const std::function<void(const std::string& row)>& skipped = {});

}  // namespace keyturn::rig
