#include "keyturn/core/pcl_baselines.h"

#include "keyturn/core/plugin.h"
#include "keyturn/core/worker_process.h"
#include "pcl_features_plugin.h"

namespace keyturn {

namespace detail {
const PclFeatures& pclFeatures() {
  static const PclFeatures* table = pluginFunction<PclFeaturesFunction>("pcl_features", "keyturn_pcl_features")();
  return *table;
}
}  // namespace detail

std::vector<Eigen::Vector3f> pclIssKeypoints(const PointSet& set, double frame_radius, double nms_radius,
                                             double gamma21, double gamma32, int min_neighbors) {
  return detail::pclFeatures().iss_keypoints(set, frame_radius, nms_radius, gamma21, gamma32, min_neighbors);
}

std::vector<float> pclEsf(const PointSet& set) { return detail::pclFeatures().esf(set); }

std::vector<float> pclEsfSeeded(const PointSet& set, unsigned seed) {
  return detail::pclFeatures().esf_seeded(set, seed);
}

std::vector<float> pclVfh(const PointSet& set, double normal_radius) {
  return detail::pclFeatures().vfh(set, normal_radius);
}

// PCL 1.13's OUR-CVFH aborts on some views (an out-of-range histogram index in
// computeRFAndShapeDistribution: an assertion in Debian's build, a stray write
// without one) and no input check we can make predicts it. It runs in the worker
// program (worker_process.h): the histogram comes back, a crash becomes an error.
std::vector<float> pclOurCvfh(const PointSet& set, double normal_radius) {
  WorkerJob request{"our-cvfh", {}};
  request.input.reserve(1 + 3 * set.size());
  request.input.push_back(static_cast<float>(normal_radius));
  for (const Eigen::Vector3f& p : set.points) request.input.insert(request.input.end(), {p.x(), p.y(), p.z()});
  return inWorkerProcess(request, "OUR-CVFH", "PCL's OUR-CVFH crashed on this view",
                         "PCL 1.13 computeRFAndShapeDistribution");
}

}  // namespace keyturn
