#pragma once
// The turntable angle each view was taken at, as multi-view fusion needs it
// (learning/view_fusion.h): from a dataset's manifest (measured_deg) or from a
// loose view's sidecar (VIEW.json beside VIEW.pcd: measured_deg).
#include <map>
#include <string>
#include <vector>

namespace keyturn::dataset {

// The sidecar beside a view file: its path with the extension replaced by ".json".
std::string sidecarPathOf(const std::string& view_path);

// The sidecar's measured_deg. Throws keyturn::Error naming the file when it is missing, not JSON,
// or holds no finite measured_deg (a view taken without a turntable has no pose).
double readViewAzimuth(const std::string& sidecar_path);

// Each view of a dataset (its row id: the view's stem relative to the root) → the manifest's
// measured_deg. Throws keyturn::Error for a folder without a manifest or views.
std::map<std::string, double> datasetAzimuths(const std::string& root);

}  // namespace keyturn::dataset
