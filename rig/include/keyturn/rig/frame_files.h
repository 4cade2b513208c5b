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

// The inverse: the PCD and the PNGs beside it, as a frame. A view that has no PNGs (imported from
// another tool) gets them from its cloud: distance from each point's range over
// non_ambiguous_range_m (0xFFFF = that range), amplitude and confidence from the cloud's fields.
// Throws keyturn::Error naming the file that is unreadable or does not match the cloud's grid.
drivers::TofFrame readFrameFiles(const std::string& pcd_path, double non_ambiguous_range_m);

}  // namespace keyturn::rig
