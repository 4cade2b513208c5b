// The plane step's RANSAC scores hypotheses with detail::countPlaneInliers instead of PCL's scalar
// loop; the count must be PCL's own (SampleConsensusModelPlane::countWithinDistance), point for
// point, on real crops, for planes through their points and planes whose band edge grazes many.
#include <gtest/gtest.h>

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/sample_consensus/sac_model_plane.h>

#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "keyturn/core/cloud_io.h"
#include "keyturn/core/filter.h"

using namespace keyturn;

TEST(PlaneInliers, CountedAsPclCountsThemOnRealCrops) {
  std::mt19937 rng(17);
  int crops = 0;
  std::size_t compared = 0, grazing = 0;
  for (const auto& e : std::filesystem::directory_iterator(std::string(KEYTURN_REAL_DATA) + "/crop")) {
    if (e.path().extension() != ".pcd" || ++crops > 8) continue;
    const PointSet set = PointSet::fromCloud(loadCloud(e.path().string()));
    pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
    std::vector<float> x, y, z;
    for (const auto& p : set.points) {
      cloud->push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
      x.push_back(p.x()), y.push_back(p.y()), z.push_back(p.z());
    }
    pcl::SampleConsensusModelPlane<pcl::PointXYZ> pcl_model(cloud, false);
    std::uniform_int_distribution<std::size_t> pick(0, set.size() - 1);
    std::normal_distribution<float> g(0.f, 1.f);
    for (int m = 0; m < 60; ++m) {
      // A random normal through a random point of the crop, and the band edge at a point's own distance
      // from it (ties at the edge are where a different sum or compare would count differently).
      Eigen::Vector3f n(g(rng), g(rng), g(rng));
      n.normalize();
      const Eigen::Vector3f& on = set.points[pick(rng)];
      const Eigen::Vector4f plane(n.x(), n.y(), n.z(), -n.dot(on));
      const Eigen::Vector3f& edge = set.points[pick(rng)];
      for (double threshold : {0.008, 0.002, std::abs(static_cast<double>(plane.head<3>().dot(edge) + plane[3]))}) {
        const std::size_t pcl_count = pcl_model.countWithinDistance(Eigen::VectorXf(plane), threshold);
        EXPECT_EQ(detail::countPlaneInliers(x, y, z, plane, threshold), pcl_count) << e.path() << ", model " << m;
        grazing += pcl_count > 0 && pcl_count < set.size();
        ++compared;
      }
    }
  }
  EXPECT_EQ(compared, 8u * 60 * 3);
  EXPECT_GT(grazing, compared / 2) << "most planes should split the crop: the comparison shows little otherwise";
}
