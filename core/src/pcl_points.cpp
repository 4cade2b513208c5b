#include "pcl_points.h"

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include "keyturn/core/cloud.h"

namespace keyturn::detail {

std::shared_ptr<PclCloud> toPcl(const std::vector<Eigen::Vector3f>& points) {
  std::shared_ptr<PclCloud> c(new PclCloud);  // PCL's aligned operator new
  c->reserve(points.size());
  for (const auto& p : points) c->push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
  return c;
}

std::shared_ptr<PclCloud> toPcl(const Cloud& cloud, std::vector<int>* index) {
  std::shared_ptr<PclCloud> c(new PclCloud);  // PCL's aligned operator new
  if (index) index->clear();
  for (std::size_t i = 0; i < cloud.points.size(); ++i) {
    const auto& p = cloud.points[i];
    if (!Cloud::isValid(p)) continue;
    c->push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
    if (index) index->push_back(static_cast<int>(i));
  }
  return c;
}

}  // namespace keyturn::detail
