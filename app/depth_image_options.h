#pragma once
// Depth images as views on a command line: the camera's intrinsics from --camera FILE or
// --fx --fy --cx --cy, the depth scale, a mask and a crop offset (core/depth_image.h). Shared by
// every command that reads views (describe, bench, classify, repeatability, import).
#include <CLI/CLI.hpp>

#include "keyturn/core/depth_image.h"
#include "keyturn/core/depth_scale_check.h"

namespace keyturn::app {

struct DepthImageFlags {
  std::string camera, mask, crop;
  std::vector<double> pinhole;  // fx fy cx cy, as given
  double fx = 0, fy = 0, cx = 0, cy = 0;
  double depth_scale = 0;  // 0: the camera file's, else 0.001

  void add(CLI::App& cmd);
  // The flags resolved (the camera file read); throws keyturn::Error on a conflict or a bad file.
  DepthImageOptions toOptions() const;
};

// How a depth image gets its intrinsics here, said after core's MissingIntrinsicsError.
inline const char* const kIntrinsicsHint = "--camera FILE, or --fx --fy --cx --cy";

// A wrong depth scale (core's DepthScaleError) in this tool's words: which --depth-scale fits, and
// why Open3D users meet it (they count units per metre).
std::string depthScaleMessage(const DepthScaleError& e);

}  // namespace keyturn::app
