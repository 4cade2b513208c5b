#include "keyturn/dataset/study_views.h"

#include <Eigen/LU>
#include <filesystem>

#include "keyturn/core/error.h"
#include "keyturn/dataset/dataset.h"
#include "keyturn/dataset/sidecars.h"

namespace fs = std::filesystem;

namespace keyturn::dataset {

std::vector<StudyView> studyViews(const std::string& input, const PoseReadOptions& poses) {
  std::vector<StudyView> out;
  if (!fs::is_directory(input)) {
    for (const auto& e : readPoses(input, poses))
      out.push_back({e.file, fs::path(input).filename().string(), std::nan(""), e.world_from_view.inverse()});
    return out;
  }
  if (poses.format != PoseFormat::Auto || !poses.views.empty())
    throw Error(input + ": a dataset's poses come from its sidecars; a pose format and a view list are for pose files");
  for (const auto& r : Dataset::readManifest(input)) {
    const auto T = readViewTransform(input + "/" + r.sidecar());
    if (!T)
      throw Error(input + ": " + r.sidecar() +
                  " has no camera_from_turntable: capture with an axis calibration (keyturn calibrate-axis), or give a pose list");
    // The sidecar's camera ← turntable at this view's angle maps the object's own
    // (table-fixed) coordinates into this camera: the object frame is the common frame.
    StudyView v{input + "/" + r.pcd(), r.key.cls + "/" + r.key.instance + "/e" + r.key.elevation, r.measured_deg, *T};
    if (poses.invert) v.view_from_common = v.view_from_common.inverse().eval();
    out.push_back(std::move(v));
  }
  return out;
}

}  // namespace keyturn::dataset
