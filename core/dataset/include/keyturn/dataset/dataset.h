#pragma once
// An SR4K-D style dataset on disk (docs/dataset-format.md):
//
//   DATASET/dataset.json                      format, version, creator
//   DATASET/manifest.csv                      one row per view, appended and synced last
//   DATASET/CLASS/INSTANCE/eLABEL/aANGLE.pcd  + _distance.png _amplitude.png _confidence.png .json
//   DATASET/snapshots/                        the studio's snapshots of live frames (no views)
//   DATASET/.keyturn-lock                     the writer's lock and who holds it (dataset_lock.h)
//
// A view exists once its manifest row does; files without a row are orphans
// of an interrupted capture and are replaced when that view is taken again.
// Temporaries a killed write left (durable_file.h) are removed when the dataset is opened.
#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "keyturn/core/cloud.h"
#include "keyturn/dataset/dataset_layout.h"
#include "keyturn/dataset/dataset_lock.h"

namespace keyturn::dataset {

struct ViewKey {
  std::string cls, instance, elevation;  // elevation label, e.g. "30"
  double commanded_deg = 0;
  bool operator==(const ViewKey& o) const;
};

struct ViewRecord {
  ViewKey key;
  double elevation_deg = 0;
  double measured_deg = 0;
  std::string captured_at;                  // ISO 8601 UTC
  std::vector<std::string> files;           // relative to the dataset root: pcd, pngs, json
  std::vector<std::string> sha256;          // one per file
  // The view's files by kind (relative to the root, "" when the row lists none).
  std::string pcd() const;
  std::string sidecar() const;              // the .json metadata
};

struct ViewMetadata {
  double elevation_deg = 0;
  double measured_deg = 0;
  std::optional<Eigen::Matrix4d> camera_from_turntable;  // none: the rig is not calibrated
  std::string pose_source;
  int frames_discarded = 0, frames_taken = 1, redos = 0;
};

// The camera a captured view's sidecar records (its "camera" object): what playback needs to
// take the view again as that camera. A field the sidecar lacks is empty.
struct SidecarCamera {
  std::string device;
  std::uint32_t serial = 0;
  std::optional<double> modulation_mhz;
  std::optional<std::uint8_t> integration_time;
  std::optional<bool> auto_exposure;
  std::optional<std::uint16_t> amplitude_threshold;
  std::optional<std::uint32_t> acquire_mode;
};

struct VerifyReport {
  std::size_t views = 0;
  std::vector<std::string> missing, corrupt, orphans, duplicates, bad_rows;
  // Temporaries of a write a kill interrupted: never part of a view, removed by the next capture,
  // so reported apart from the orphans and not a problem of the dataset's views.
  std::vector<std::string> temporaries;
  bool ok() const { return missing.empty() && corrupt.empty() && orphans.empty() && duplicates.empty() && bad_rows.empty(); }
  // A dataset without views is not a good one (a capture that never took its first view).
  bool good() const { return ok() && views > 0; }
  // What keyturn verify prints: one line per problem file, then the counts and OK / EMPTY / PROBLEMS.
  std::string text(const std::string& root) const;
};

class Dataset {
 public:
  // Opens or creates the dataset folder for writing, holding its lock (dataset_lock.h: throws
  // DatasetBusyError while another writer has it) until destroyed; removes the temporaries an
  // interrupted write left in its view folders; reads an existing manifest.
  explicit Dataset(std::string root);
  // The same with the lock already taken (a capture takes it before its devices write into .sim/).
  Dataset(std::string root, DatasetLock lock);
  const std::string& root() const { return root_; }
  std::size_t temporariesRemoved() const { return temporaries_removed_; }  // by the constructor
  const std::vector<ViewRecord>& views() const { return views_; }
  bool has(const ViewKey& key) const;
  // A captured view: write_files writes the view's files durably (given the absolute path of its
  // PCD, DATASET/CLASS/INSTANCE/eLABEL/aANGLE.pcd) and returns every path it wrote; then the sidecar
  // (recording the camera) and the manifest row. Returns the record. rig::writeFrameView writes a
  // camera frame this way.
  using FileWriter = std::function<std::vector<std::string>(const std::string& pcd_path)>;
  ViewRecord writeCaptured(const ViewKey& key, const ViewMetadata& meta, const SidecarCamera& camera,
                           const FileWriter& write_files);
  // A view from another tool's files (keyturn import): its cloud as the view's PCD and a sidecar
  // naming the source file and the importer (no camera settings, no raw images), then its row.
  ViewRecord writeImported(const ViewKey& key, const ViewMetadata& meta, const Cloud& cloud, const std::string& source,
                           const std::string& importer);
  std::string viewStem(const ViewKey& key) const;  // relative path without extension

  // CRLF line endings and a UTF-8 byte order mark (as spreadsheets save CSV) are accepted; a first line
  // that is not the header throws keyturn::Error naming the file and what differs. Malformed rows go
  // to bad_rows.
  static std::vector<ViewRecord> readManifest(const std::string& root, std::vector<std::string>* bad_rows = nullptr);
  static VerifyReport verify(const std::string& root);

 private:
  ViewRecord beginView(const ViewKey& key, const ViewMetadata& meta, std::string& abs_stem) const;
  void removeFilesWithoutRow(const std::string& abs_stem) const;
  ViewRecord commitView(ViewRecord r, const std::string& abs_stem, const std::string& sidecar_json);
  std::string root_;
  DatasetLock lock_;
  std::vector<ViewRecord> views_;
  std::size_t temporaries_removed_ = 0;
};

// Removes a dataset folder that holds no views (no manifest, or one without rows): what a capture
// that failed before its first view leaves, which verify would otherwise call a good, empty dataset.
// A folder holding any other file, or a manifest keyturn cannot read, is kept.
void removeDatasetWithoutViews(const std::string& root);

std::string manifestHeader();
std::string sha256File(const std::string& path);  // lowercase hex; throws keyturn::Error

}  // namespace keyturn::dataset
