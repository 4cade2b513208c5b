#pragma once
// Every path of a dataset folder, named once (issue 48; docs/dataset-format.md). A dataset root holds:
//   manifest.csv        one row per view (dataset.h)
//   dataset.json        what the folder is: format, version, the keyturn that made it
//   calibration.json    the turntable's axis calibration, when the capture was given one (sidecars.h)
//   .keyturn/           the feature cache (feature_cache_files.h)
//   .keyturn-lock       the writers' lock (dataset_lock.h)
//   .sim/               the simulated rig's state, when a simulated rig captured it
//   snapshots/          frames the studio saved beside the views (no view's)
//   CLASS/INSTANCE/eELEVATION/aANGLE.pcd, its frame images (view_files.h) and its .json sidecar
// Nothing else in the project spells these (structure.dataset_layout_names checks it).
#include <string>

namespace keyturn::dataset {

inline constexpr const char* kManifestFile = "manifest.csv";
inline constexpr const char* kDescriptionFile = "dataset.json";
inline constexpr const char* kCalibrationFile = "calibration.json";
inline constexpr const char* kKeyturnFolder = ".keyturn";
inline constexpr const char* kLockFile = ".keyturn-lock";
inline constexpr const char* kSimulatorFolder = ".sim";
inline constexpr const char* kSnapshotsFolder = "snapshots";

// ROOT/NAME for one of the names above.
inline std::string datasetPath(const std::string& root, const char* name) { return root + "/" + name; }
inline std::string manifestPath(const std::string& root) { return datasetPath(root, kManifestFile); }

}  // namespace keyturn::dataset
