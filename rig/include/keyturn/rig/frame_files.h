#pragma once
// One camera frame on disk: an organized PCD (x, y, z, amplitude, confidence;
// binary_compressed) plus 16-bit PNGs of the raw distance, amplitude and
// confidence images beside it. Each file is written to a temporary name,
// synced and renamed, so a reader (or a crash) never leaves half a file.
#include <string>
#include <vector>

#include "keyturn/drivers/tof_camera.h"

namespace keyturn::rig {

// pcd_path "dir/view.pcd" → also dir/view_distance.png, _amplitude.png, _confidence.png.
// Returns every path written.
std::vector<std::string> writeFrameFiles(const std::string& pcd_path, const drivers::TofFrame& frame);

}  // namespace keyturn::rig
