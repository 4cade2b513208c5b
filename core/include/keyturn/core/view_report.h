#pragma once
// One described view as `keyturn describe` reports it (docs/formats.md): its CSV
// row (counts, the filter's report, every PDF bin); --explain's text is view_explanation.h.
#include <string>
#include <vector>

#include "keyturn/core/descriptor.h"

namespace keyturn {

// file,points,keypoints,…,filter_flag, then FEATURE_BIN for each feature's bins.
std::string describeCsvHeader(const std::vector<Feature>& features, int bins);
// The row of one view (the file quoted when it holds a comma, a quote or a newline).
std::string describeCsvRow(const std::string& file, const ViewDescriptor& d);

}  // namespace keyturn
