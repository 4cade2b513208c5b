// PCL's ESF draws its random point triples with rand() after calling
// srand(time(nullptr)) inside computeESF, so two runs in different seconds give
// different histograms and no srand() before compute() can fix that. Here the
// ESF template is instantiated for a point type of keyturn's own (so PCL's
// precompiled instance is not used) with time() replaced by the caller's seed:
// the same cloud and seed give the same histogram, every run.
// Header-only PCL in this file: its templates are instantiated here, for EsfPoint.
#define PCL_NO_PRECOMPILE
#include <pcl/common/distances.h>
#include <pcl/common/transforms.h>
#include <pcl/features/feature.h>
#include <pcl/pcl_base.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/search/kdtree.h>
#include <pcl/search/organized.h>

#include <ctime>
#include <mutex>
#include <vector>

#include "pcl_plugin_parts.h"

namespace keyturn::esf_detail {
std::time_t seed = 7;
inline std::time_t seededTime(std::time_t*) { return seed; }
}  // namespace keyturn::esf_detail

// NOLINTNEXTLINE: the one place keyturn redirects a library call by macro, see above.
#define time(arg) ::keyturn::esf_detail::seededTime(arg)
#include <pcl/features/esf.h>  // brings impl/esf.hpp (PCL_NO_PRECOMPILE)
#undef time

namespace keyturn::esf_detail {
struct EIGEN_ALIGN16 EsfPoint {
  PCL_ADD_POINT4D;
  PCL_MAKE_ALIGNED_OPERATOR_NEW
};
}  // namespace keyturn::esf_detail

POINT_CLOUD_REGISTER_POINT_STRUCT(keyturn::esf_detail::EsfPoint, (float, x, x)(float, y, y)(float, z, z))

namespace keyturn {

std::vector<float> pcl_plugin::esfSeeded(const PointSet& set, unsigned seed) {
  // rand() is process-wide state: one ESF at a time.
  static std::mutex mutex;
  std::lock_guard<std::mutex> lock(mutex);
  pcl::PointCloud<esf_detail::EsfPoint>::Ptr cloud(new pcl::PointCloud<esf_detail::EsfPoint>);
  cloud->resize(set.size());
  for (std::size_t i = 0; i < set.size(); ++i) {
    (*cloud)[i].x = set.points[i].x();
    (*cloud)[i].y = set.points[i].y();
    (*cloud)[i].z = set.points[i].z();
  }
  esf_detail::seed = static_cast<std::time_t>(seed);
  pcl::ESFEstimation<esf_detail::EsfPoint, pcl::ESFSignature640> esf;
  esf.setInputCloud(cloud);
  pcl::PointCloud<pcl::ESFSignature640> out;
  esf.compute(out);
  if (out.empty()) return {};
  return std::vector<float>(out[0].histogram, out[0].histogram + 640);
}

}  // namespace keyturn
