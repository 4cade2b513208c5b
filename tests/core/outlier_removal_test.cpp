// removeStatisticalOutliers keeps PCL's rule and arithmetic but searches in one batch: the same
// points must go as with pcl::StatisticalOutlierRemoval, on real crops and on a cloud with outliers.
#include <gtest/gtest.h>

#include <pcl/filters/statistical_outlier_removal.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "keyturn/core/cloud_io.h"
#include "keyturn/core/filter.h"
#include "support/synthetic_clouds.h"

using namespace keyturn;

namespace {

// The indices of the valid points of `cloud` that pcl::StatisticalOutlierRemoval keeps.
std::vector<int> keptByPcl(const Cloud& cloud, int k, float std_mul) {
  pcl::PointCloud<pcl::PointXYZ>::Ptr pts(new pcl::PointCloud<pcl::PointXYZ>);
  std::vector<int> index;
  for (std::size_t i = 0; i < cloud.points.size(); ++i)
    if (Cloud::isValid(cloud.points[i])) {
      const auto& p = cloud.points[i];
      pts->push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
      index.push_back(static_cast<int>(i));
    }
  pcl::StatisticalOutlierRemoval<pcl::PointXYZ> sor;
  sor.setInputCloud(pts);
  sor.setMeanK(k);
  sor.setStddevMulThresh(std_mul);
  pcl::Indices kept;
  sor.filter(kept);
  std::vector<int> out;
  for (auto i : kept) out.push_back(index[static_cast<std::size_t>(i)]);
  return out;
}

std::vector<int> keptByKeyturn(Cloud cloud, int k, float std_mul) {
  removeStatisticalOutliers(cloud, k, std_mul);
  std::vector<int> out;
  for (std::size_t i = 0; i < cloud.points.size(); ++i)
    if (Cloud::isValid(cloud.points[i])) out.push_back(static_cast<int>(i));
  return out;
}

}  // namespace

TEST(OutlierRemoval, RemovesWhatPclRemovesOnACloudWithOutliers) {
  auto pts = test::cubeSurface(0.1f, 15, Eigen::Vector3f(0, 0, 1));
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-0.3f, 0.3f);
  for (int i = 0; i < 40; ++i) pts.emplace_back(u(rng), u(rng), 1.f + u(rng));
  const Cloud c = test::unorganized(pts);
  for (int k : {4, 12, 30})
    for (float m : {0.5f, 1.f, 2.f}) {
      const auto pcl_kept = keptByPcl(c, k, m);
      EXPECT_EQ(keptByKeyturn(c, k, m), pcl_kept) << "k " << k << ", std_mul " << m;
      EXPECT_LT(pcl_kept.size(), pts.size()) << "the rule removed nothing: the comparison shows nothing";
    }
}

#ifdef KEYTURN_REAL_DATA
TEST(OutlierRemoval, RemovesWhatPclRemovesOnRealCrops) {
  int crops = 0;
  std::size_t removed = 0;
  for (const auto& e : std::filesystem::directory_iterator(std::string(KEYTURN_REAL_DATA) + "/crop")) {
    if (e.path().extension() != ".pcd") continue;
    const Cloud c = loadCloud(e.path().string());
    const FilterOptions o;
    const auto pcl_kept = keptByPcl(c, o.sor_k, o.sor_std_mul);
    EXPECT_EQ(keptByKeyturn(c, o.sor_k, o.sor_std_mul), pcl_kept) << e.path();
    removed += c.validCount() - pcl_kept.size();
    ++crops;
  }
  EXPECT_EQ(crops, 38);
  EXPECT_GT(removed, 0u);
}
#endif
