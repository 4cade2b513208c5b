#pragma once
// PCL's own detectors and global descriptors on the same cloud, for the bench
// and for cross-checks: ISSKeypoint3D, ESF and VFH (with its normals).
#include <Eigen/Core>
#include <vector>

#include "keyturn/core/cloud.h"

namespace keyturn {

// PCL ISSKeypoint3D with radii in metres (salient = frame, non-max = nms).
std::vector<Eigen::Vector3f> pclIssKeypoints(const PointSet& set, double frame_radius,
                                             double nms_radius, double gamma21, double gamma32,
                                             int min_neighbors);
// ESF (640 bins). PCL 1.13 reseeds rand() from time() inside compute, so two
// runs in different seconds differ; timing is unaffected (see docs/benchmarks.md).
std::vector<float> pclEsf(const PointSet& set);

// ESF made repeatable: the same cloud and seed give the same histogram
// (pcl_esf_seeded.cpp says how). Serialised: ESF uses the global rand().
std::vector<float> pclEsfSeeded(const PointSet& set, unsigned seed);

// OUR-CVFH (308 bins): PCL computes one histogram per smooth region; this is
// the first one (the region PCL lists first), empty when PCL finds none.
// Runs in the worker program (worker_process.h): PCL 1.13 crashes on some views, which then throws
// keyturn::Error instead of taking the caller down.
std::vector<float> pclOurCvfh(const PointSet& set, double normal_radius);
// VFH (308 bins) with normals from a radius search of normal_radius metres.
std::vector<float> pclVfh(const PointSet& set, double normal_radius);

}  // namespace keyturn
