#pragma once
// Other people's datasets as keyturn datasets (keyturn import, docs/dataset-format.md): a layout
// is read into a list of views (class, instance, elevation, angle, source file), then each view is
// read as any view is (loadCloud: PCD, PLY or depth PNG; or the layout's own reader) and written into DATASET as its PCD and a
// sidecar naming the source (copied, never referenced), with its manifest row. What a layout
// cannot use is reported in one line per file, and the rest is imported.
#include <cstddef>
#include <Eigen/Core>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "keyturn/core/cloud.h"
#include "keyturn/core/depth_image.h"
#include "keyturn/dataset/dataset.h"

namespace keyturn::dataset {

struct ImportedView {
  ViewKey key;
  double elevation_deg = 0;  // NaN when the layout does not say
  std::string file;          // the source view (absolute or relative to the working folder)
  std::string angle_note;    // how the angle was found, for the sidecar's pose_source
  std::optional<Eigen::Matrix4d> camera_from_turntable;  // the layout's measured pose, when it has one
  std::function<Cloud()> read;  // the layout's own reader (BigBIRD's HDF5); empty: loadCloud(file)
};

struct ImportPlan {
  std::vector<ImportedView> views;
  std::vector<std::string> problems;  // "FILE: what is wrong", one per file
};

// Washington RGB-D Object Dataset: CATEGORY/INSTANCE/INSTANCE_VIDEO_FRAME.pcd, or the cropped
// INSTANCE_VIDEO_FRAME_depthcrop.png with its _maskcrop.png and _loc.txt. Videos 1, 2, 4 are the
// 30°, 45°, 60° elevations; the angle is 360° × (frame − first) / (frames in the video's span).
ImportPlan planWashingtonImport(const std::string& source);
// CLASS/INSTANCE/[eLABEL/]VIEW.{pcd,ply,png}. VIEW named aANGLE gives its angle; other views are
// spread evenly over one turn in name order. No eLABEL folder: the elevation label is "unknown".
ImportPlan planFoldersImport(const std::string& source);
// BigBIRD (Singh et al., ICRA 2014): OBJECT/NP{1..5}_ANGLE.h5 depth images (uint16, 100 µm) of five
// cameras one above the other, with OBJECT/calibration.h5, OBJECT/poses/NP5_ANGLE_pose.h5 and
// optional OBJECT/masks/NPi_ANGLE_mask.pbm. Class = the object, or its class in `categories` (a
// CSV with class and instance columns, instance = the object's folder) when given; instance = the
// object; elevation label = the camera (NP1 … NP5); angle = ANGLE; the pose is the camera's ← the
// turntable's at that angle.
ImportPlan planBigbirdImport(const std::string& source, const std::string& categories = "");

// The Washington dataset's Kinect (its depthToCloud.m: focal length 570.3 px, centre (320, 240)
// 1-based = (319, 239) 0-based; depth in millimetres).
DepthIntrinsics washingtonIntrinsics();

struct ImportOptions {
  std::string format;        // washington, folders or bigbird
  std::string source, out;
  std::string categories;    // bigbird only: class,instance CSV giving each object's class
  DepthImageOptions depth;   // for depth PNGs; washington without intrinsics: washingtonIntrinsics()
  std::function<void(std::size_t done, std::size_t total)> progress;  // may be empty
};

struct ImportReport {
  std::size_t imported = 0, already = 0;  // already: in DATASET from an earlier run, left as they are
  std::vector<std::string> problems;
  // One line per problem, then "SOURCE → OUT: N views imported, …".
  std::string text(const ImportOptions& o) const;
};

// Throws keyturn::Error for an unknown format, a source that is not a folder, an OUT that is
// neither new, empty nor a keyturn dataset, depth images without intrinsics, or no view at all.
ImportReport importDataset(const ImportOptions& options);

}  // namespace keyturn::dataset
