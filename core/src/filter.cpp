#include "keyturn/core/filter.h"

#include <pcl/ModelCoefficients.h>
#include <pcl/filters/statistical_outlier_removal.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/sample_consensus/method_types.h>
#include <pcl/sample_consensus/model_types.h>
#include <pcl/segmentation/sac_segmentation.h>

#include <cmath>
#include <numeric>

#include "keyturn/core/radius_search.h"

namespace keyturn {
namespace {

const Eigen::Vector3f kNaN = Eigen::Vector3f::Constant(std::nanf(""));

// Valid points as a PCL cloud plus the cloud index of each.
pcl::PointCloud<pcl::PointXYZ>::Ptr validPoints(const Cloud& cloud, std::vector<int>& index) {
  pcl::PointCloud<pcl::PointXYZ>::Ptr out(new pcl::PointCloud<pcl::PointXYZ>);
  index.clear();
  for (std::size_t i = 0; i < cloud.points.size(); ++i) {
    const auto& p = cloud.points[i];
    if (!Cloud::isValid(p)) continue;
    out->push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
    index.push_back(static_cast<int>(i));
  }
  return out;
}

}  // namespace

void cropRange(Cloud& cloud, float min_range, float max_range) {
  for (auto& p : cloud.points) {
    if (!Cloud::isValid(p)) continue;
    const float r = p.norm();
    if ((min_range > 0 && r < min_range) || (max_range > 0 && r > max_range)) p = kNaN;
  }
}

void cropBox(Cloud& cloud, const Eigen::Vector3f& box_min, const Eigen::Vector3f& box_max) {
  for (auto& p : cloud.points)
    if (Cloud::isValid(p) && ((p.array() < box_min.array()).any() || (p.array() > box_max.array()).any()))
      p = kNaN;
}

std::size_t removeJumpEdges(Cloud& cloud, float angle_deg) {
  if (!cloud.organized()) return 0;
  const int w = static_cast<int>(cloud.width), h = static_cast<int>(cloud.height);
  // A mixed pixel lies between a foreground and a background surface along its
  // own ray: it has a neighbour nearly straight in front of it AND one nearly
  // straight behind it. The true edge pixels of either surface have only one
  // such neighbour and are kept, so a real surface is never cut back.
  const float cos_limit = std::cos(angle_deg * static_cast<float>(M_PI) / 180.0f);
  std::vector<char> remove(cloud.points.size(), 0);
  for (int v = 0; v < h; ++v) {
    for (int u = 0; u < w; ++u) {
      const std::size_t i = static_cast<std::size_t>(v) * w + u;
      const Eigen::Vector3f& p = cloud.points[i];
      if (!Cloud::isValid(p)) continue;
      const Eigen::Vector3f ray = p.normalized();
      bool nearer = false, farther = false;
      for (int dv = -1; dv <= 1; ++dv) {
        for (int du = -1; du <= 1; ++du) {
          const int uu = u + du, vv = v + dv;
          if ((du == 0 && dv == 0) || uu < 0 || vv < 0 || uu >= w || vv >= h) continue;
          const Eigen::Vector3f& q = cloud.points[static_cast<std::size_t>(vv) * w + uu];
          if (!Cloud::isValid(q)) continue;
          const Eigen::Vector3f d = q - p;
          const float along = ray.dot(d);
          if (std::abs(along) > cos_limit * d.norm()) (along < 0 ? nearer : farther) = true;
        }
      }
      remove[i] = nearer && farther;
    }
  }
  std::size_t n = 0;
  for (std::size_t i = 0; i < remove.size(); ++i)
    if (remove[i]) {
      cloud.points[i] = kNaN;
      ++n;
    }
  return n;
}

bool removeDominantPlane(Cloud& cloud, const FilterOptions& options, Eigen::Vector4f* plane) {
  std::vector<int> index;
  auto pts = validPoints(cloud, index);
  if (pts->size() < 10) return false;
  pcl::SACSegmentation<pcl::PointXYZ> seg(false);  // fixed seed: same cloud, same plane
  seg.setOptimizeCoefficients(true);
  seg.setModelType(pcl::SACMODEL_PLANE);
  seg.setMethodType(pcl::SAC_RANSAC);
  seg.setDistanceThreshold(options.plane_distance);
  seg.setMaxIterations(options.plane_iterations);
  seg.setInputCloud(pts);
  pcl::PointIndices inliers;
  pcl::ModelCoefficients coeff;
  seg.segment(inliers, coeff);
  if (coeff.values.size() != 4 ||
      inliers.indices.size() < options.plane_min_fraction * static_cast<float>(pts->size()))
    return false;
  Eigen::Vector4f pl(coeff.values[0], coeff.values[1], coeff.values[2], coeff.values[3]);
  pl /= pl.head<3>().norm();
  if (pl[3] < 0) pl = -pl;  // the camera (origin) on the positive side
  // Everything within the band or behind the plane (under the table) goes.
  for (std::size_t k = 0; k < index.size(); ++k) {
    const auto& p = cloud.points[index[k]];
    if (pl.head<3>().dot(p) + pl[3] < options.plane_distance) cloud.points[index[k]] = kNaN;
  }
  if (plane) *plane = pl;
  return true;
}

void keepLargestCluster(Cloud& cloud, float tolerance) {
  // Connected components of the tolerance-ball graph, by breadth-first search
  // over the project's radius search (pixel grid for organized views).
  const PointSet set = PointSet::fromCloud(cloud);
  if (set.size() < 2) return;
  const RadiusSearch search(set);
  std::vector<int> label(set.size(), -1), queue, nb;
  int best_label = -1;
  std::size_t best_size = 0;
  for (std::size_t s = 0; s < set.size(); ++s) {
    if (label[s] >= 0) continue;
    const int id = static_cast<int>(s);
    queue.assign(1, id);
    label[s] = id;
    for (std::size_t head = 0; head < queue.size(); ++head) {
      search.radius(queue[head], tolerance, nb);
      for (int j : nb)
        if (label[j] < 0) {
          label[j] = id;
          queue.push_back(j);
        }
    }
    if (queue.size() > best_size) {
      best_size = queue.size();
      best_label = id;
    }
  }
  // Map compact indices back to cloud indices.
  std::size_t k = 0;
  for (auto& p : cloud.points) {
    if (!Cloud::isValid(p)) continue;
    if (label[k++] != best_label) p = kNaN;
  }
}

void removeStatisticalOutliers(Cloud& cloud, int k, float std_mul) {
  std::vector<int> index;
  auto pts = validPoints(cloud, index);
  if (pts->size() <= static_cast<std::size_t>(k)) return;
  pcl::StatisticalOutlierRemoval<pcl::PointXYZ> sor(true);
  sor.setInputCloud(pts);
  sor.setMeanK(k);
  sor.setStddevMulThresh(std_mul);
  pcl::Indices kept;
  sor.filter(kept);
  std::vector<char> keep(pts->size(), 0);
  for (auto i : kept) keep[i] = 1;
  for (std::size_t j = 0; j < index.size(); ++j)
    if (!keep[j]) cloud.points[index[j]] = kNaN;
}

Cloud filterCloud(const Cloud& input, const FilterOptions& o, FilterReport* report) {
  Cloud cloud = input;
  FilterReport r;
  r.input_valid = cloud.validCount();
  if (o.crop_range) cropRange(cloud, o.min_range, o.max_range);
  if (o.crop_box) cropBox(cloud, o.box_min, o.box_max);
  r.after_crop = cloud.validCount();
  if (o.jump_edge) removeJumpEdges(cloud, o.jump_edge_angle_deg);
  r.after_jump_edge = cloud.validCount();
  if (o.remove_plane) r.plane_found = removeDominantPlane(cloud, o, &r.plane);
  r.after_plane = cloud.validCount();
  if (o.largest_cluster) keepLargestCluster(cloud, o.cluster_tolerance);
  r.after_cluster = cloud.validCount();
  if (o.outlier_removal) removeStatisticalOutliers(cloud, o.sor_k, o.sor_std_mul);
  r.after_outliers = cloud.validCount();
  if (report) *report = r;
  return cloud;
}

}  // namespace keyturn
