// nearestSquaredDistances must give, value for value, the squared distances PCL's exact k-d tree
// (KdTreeFLANN) gives for each point's k nearest: on a real crop, on clouds with twins and far
// outliers (the shells and the every-point fallback), on a line and a plane (a degenerate box).
#include <gtest/gtest.h>

#include <pcl/kdtree/kdtree_flann.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <random>
#include <string>
#include <vector>

#include "keyturn/core/cloud_io.h"
#include "keyturn/core/nearest_neighbours.h"
#include "support/synthetic_clouds.h"

using namespace keyturn;

namespace {

std::vector<float> byKdTree(const std::vector<Eigen::Vector3f>& pts, int k) {
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  for (const auto& p : pts) cloud->push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
  pcl::KdTreeFLANN<pcl::PointXYZ> tree;
  tree.setInputCloud(cloud);
  std::vector<float> out;
  pcl::Indices idx;
  std::vector<float> d2;
  for (const auto& q : *cloud) {
    tree.nearestKSearch(q, k, idx, d2);
    out.insert(out.end(), d2.begin(), d2.end());
  }
  return out;
}

// How many of the values differ (0 when the two agree exactly).
std::size_t differing(const std::vector<float>& a, const std::vector<float>& b) {
  if (a.size() != b.size()) return std::max(a.size(), b.size());
  std::size_t n = 0;
  for (std::size_t i = 0; i < a.size(); ++i) n += a[i] != b[i];
  return n;
}

}  // namespace

TEST(NearestNeighbours, SameSquaredDistancesAsPclsKdTreeOnARealCrop) {
  const Cloud crop = loadCloud(std::string(KEYTURN_REAL_DATA) + "/crop/learn0_o1.pcd");
  const auto pts = PointSet::fromCloud(crop).points;
  ASSERT_GT(pts.size(), 20000u);
  for (int k : {2, 13}) {
    const auto got = nearestSquaredDistances(pts, k);
    ASSERT_EQ(got.size(), pts.size() * k);
    EXPECT_EQ(differing(got, byKdTree(pts, k)), 0u) << "k " << k;
  }
}

TEST(NearestNeighbours, SameAsTheKdTreeWithTwinsFarOutliersAndFlatOrLinearSets) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> u(-0.05f, 0.05f);
  auto surface = test::cubeSurface(0.1f, 12, Eigen::Vector3f(0, 0, 1));
  for (int i = 0; i < 30; ++i) surface.push_back(surface[static_cast<std::size_t>(i) * 7]);  // twins
  for (int i = 0; i < 8; ++i) surface.emplace_back(3.f * u(rng) * 20, 2.f, 1.f + 40 * u(rng));  // metres away
  std::vector<Eigen::Vector3f> plane, line, clump;
  for (int i = 0; i < 400; ++i) plane.emplace_back(u(rng), u(rng), 0.7f);
  for (int i = 0; i < 300; ++i) line.emplace_back(u(rng), 0.f, 0.f);
  for (int i = 0; i < 50; ++i) clump.emplace_back(0.25f, -0.5f, 1.25f);  // every point at one place
  const std::vector<std::pair<const char*, const std::vector<Eigen::Vector3f>*>> sets = {
      {"surface with twins and outliers", &surface}, {"plane", &plane}, {"line", &line}, {"one place", &clump}};
  for (const auto& [name, pts] : sets)
    for (int k : {1, 2, 5, 13, 31}) {
      const auto got = nearestSquaredDistances(*pts, k);
      EXPECT_EQ(differing(got, byKdTree(*pts, k)), 0u) << name << ", k " << k;
    }
}

TEST(NearestNeighbours, AtMostAsManyNeighboursAsPoints) {
  const std::vector<Eigen::Vector3f> three = {{0, 0, 0}, {1, 0, 0}, {0, 2, 0}};
  EXPECT_EQ(nearestSquaredDistances(three, 5), (std::vector<float>{0, 1, 4, 0, 1, 5, 0, 4, 5}));
  EXPECT_TRUE(nearestSquaredDistances(three, 0).empty());
  EXPECT_TRUE(nearestSquaredDistances({}, 3).empty());
}
