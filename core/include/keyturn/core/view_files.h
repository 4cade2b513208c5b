#pragma once
// Expanding the FILES_OR_FOLDERS arguments of a command into view files.
#include <string>
#include <vector>

namespace keyturn {

// The images a captured frame keeps beside its PCD (VIEW.pcd → VIEW_distance.png, …; rig's
// frame_files.h writes and reads them, a dataset keeps them with its views).
inline constexpr const char* kDistanceImageSuffix = "_distance.png";
inline constexpr const char* kAmplitudeImageSuffix = "_amplitude.png";
inline constexpr const char* kConfidenceImageSuffix = "_confidence.png";

struct ViewFileList {
  std::vector<std::string> files;   // in argument order, folders sorted
  std::vector<std::string> errors;  // one line per argument that could not be used
};

// Folders contribute every .pcd/.ply below them (recursively, sorted) and, when depth images are
// being read (intrinsics given), every .png but masks, colour crops and a frame's raw images.
ViewFileList collectViewFiles(const std::vector<std::string>& inputs, bool depth_images = false);

// A PNG beside depth images that is not a view: a mask (_mask, _maskcrop), a colour image (_crop,
// _rgb) or a frame's raw image (_distance, _amplitude, _confidence). `name` is the file's name.
bool isCompanionImage(const std::string& name);

}  // namespace keyturn
