#pragma once
// The working resolution: a view is described at a spacing set by its own size,
// not by the sensor, so that the chain's cost stays bounded at any density and one
// object seen by an SR4000 at 0.5 m and by a 640 x 480 sensor at 0.7 m gives
// keypoints of comparable count and place (docs/filtering.md has the rule).
#include <cstddef>
#include <string>

#include "keyturn/core/cloud.h"

namespace keyturn {

// Where the voxel grid of the subsampling lies.
//  ObjectGrid (default): origin at the view's centroid, axes along its principal axes, so which
//    points survive depends on the object alone: moving or turning the view moves the same points
//    (docs/descriptors.md, "Stability").
//  CameraGrid: origin and axes of the camera frame (before issue 30): a view moved by a millimetre
//    keeps other points. Kept for feature specifications written before the choice existed.
enum class VoxelAnchor { ObjectGrid, CameraGrid };
const char* voxelAnchorName(VoxelAnchor anchor);       // "object", "camera"
VoxelAnchor parseVoxelAnchor(const std::string& name);  // throws keyturn::Error

// Which points stand for an occupied voxel.
//  Means (default): the mean of the voxel's points (PCL's VoxelGrid rule), placed at the pixel of its
//    nearest measured point in an organized view. Each voxel decides alone, so a point that crosses
//    a voxel face changes two means a little and nothing else, and the mean also averages the
//    sensor's noise.
//  Thinned: the measured point nearest the voxel's mean, the representatives then thinned to at
//    least s apart in index order (before issue 30). Greedy thinning cascades: one changed
//    representative changes every later decision near it.
enum class VoxelPoints { Means, Thinned };
const char* voxelPointsName(VoxelPoints points);       // "means", "thinned"
VoxelPoints parseVoxelPoints(const std::string& name);  // throws keyturn::Error

struct WorkingResolutionOptions {
  bool enabled = true;
  // Working spacing s = E / samples_across, E = 2 x the RMS distance of the points from their centroid.
  double samples_across = 40.0;
  // A view whose points already fall into at least this fraction of distinct s-voxels
  // is no denser than the working spacing and is kept as it is.
  double keep_fraction = 0.8;
  VoxelAnchor anchor = VoxelAnchor::ObjectGrid;
  VoxelPoints points = VoxelPoints::Means;
  // Means: the voxel's side in multiples of s (larger than s: unthinned means lie closer together
  // than thinned points, and this keeps the number of points, and the chain's cost, about the same).
  double mean_voxel = 1.5;
};

struct WorkingResolutionReport {
  double extent = 0;   // E, metres
  double spacing = 0;  // s, metres
  bool subsampled = false;
  std::size_t before = 0, after = 0;
  // The points are voxel means: each sits at its nearest measured point's pixel but off that pixel's
  // ray, so the pixel grid is no index of them (PointSet::forgetPixels before searching).
  bool off_pixel_rays = false;
};

// Brings a view denser than the working spacing s to about s (VoxelPoints says how). The layout is
// kept: an organized view stays organized, the dropped pixels NaN.
void subsampleToWorkingResolution(Cloud& cloud, const WorkingResolutionOptions& options,
                                  WorkingResolutionReport* report = nullptr);

}  // namespace keyturn
