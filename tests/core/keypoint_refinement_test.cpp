// Keypoint refinement (issue 30): the chain's keypoints, found on voxel means, moved onto the
// measured points, where they no longer depend on where the working resolution's grid lies.
#include <gtest/gtest.h>

#include <string>

#include "keyturn/core/cloud_io.h"
#include "keyturn/core/descriptor.h"
#include "keyturn/core/keypoint_detectors.h"
#include "keyturn/core/keypoint_refinement.h"
#include "keyturn/core/radius_search.h"

namespace keyturn {
namespace {

Cloud realCrop(const std::string& name) { return loadCloud(std::string(KEYTURN_REAL_DATA) + "/crop/" + name + ".pcd"); }

DescriptorOptions refining(double samples_across = 40.0) {
  DescriptorOptions o;
  o.features = {Feature::KPD2, Feature::KPA3};
  o.working.samples_across = samples_across;
  o.refine.enabled = true;
  return o;
}

// Keypoints of `a` with a keypoint of `b` within `r`.
int matched(const std::vector<Eigen::Vector3f>& a, const std::vector<Eigen::Vector3f>& b, double r) {
  int n = 0;
  for (const auto& p : a)
    for (const auto& q : b)
      if ((p - q).norm() < r) {
        ++n;
        break;
      }
  return n;
}

TEST(KeypointRefinement, OffByDefaultAndTheMeasuredViewIsKeptOnlyForIt) {
  const Cloud view = realCrop("learn0_o2");
  EXPECT_FALSE(DescriptorOptions().refine.enabled);
  EXPECT_EQ(prepareView(view, DescriptorOptions()).measured.size(), 0u);
  const PreparedView v = prepareView(view, refining());
  ASSERT_TRUE(v.working.subsampled);
  EXPECT_EQ(v.measured.size(), v.working.before);  // every point the working resolution was given
  EXPECT_GT(v.measured.size(), v.points.size());
}

TEST(KeypointRefinement, EachKeypointMovesOntoAMeasuredPointWithinItsWindow) {
  for (const char* name : {"learn0_o1", "learn10_o1", "learn34_o2"}) {  // each subsampled
    const Cloud view = realCrop(name);
    DescriptorOptions plain = refining();
    plain.refine.enabled = false;
    const ViewDescriptor before = describeView(view, plain);
    const ViewDescriptor after = describeView(view, refining());
    const PreparedView v = prepareView(view, refining());
    ASSERT_EQ(after.keypointCount(), before.keypointCount()) << name << ": refinement keeps the chain's choice";
    EXPECT_EQ(after.keypoint_index, before.keypoint_index) << name << ": geodesics start where the chain found them";
    // The first stage's window at the chain's scale, then the fine stage's at twice the measured
    // spacing near the keypoints (bounded here by twice the mean spacing: crops are denser nearer).
    const KeypointRefinementOptions r;
    const double window = r.window * plain.iss.nms_radius * after.resolution +
                          r.fine_window * plain.iss.nms_radius * r.fine_scale * 2 * cloudResolution(v.measured);
    int moved = 0;
    for (std::size_t k = 0; k < after.keypoints.size(); ++k) {
      const double shift = (after.keypoints[k] - before.keypoints[k]).norm();
      EXPECT_LE(shift, window * (1 + 1e-6)) << name << " keypoint " << k;
      moved += shift > 0;
      bool measured = false;
      for (const auto& p : v.measured.points) measured |= p == after.keypoints[k];
      EXPECT_TRUE(measured || shift == 0) << name << " keypoint " << k << " is no measured point";
    }
    EXPECT_GT(2 * moved, static_cast<int>(after.keypoints.size())) << name << ": most keypoints sit on voxel means";
  }
}

// What refinement is for: two working resolutions lay different grids on the same points; the
// keypoints found on each land on the same measured points far more often once refined.
TEST(KeypointRefinement, RefinedKeypointsDependLessOnTheWorkingGrid) {
  int plain_matched = 0, refined_matched = 0, total = 0;
  for (const char* name : {"learn0_o1", "learn10_o1", "learn12_o1", "learn34_o2"}) {  // each subsampled
    const Cloud view = realCrop(name);
    DescriptorOptions a = refining(40.0), b = refining(44.0);
    const ViewDescriptor ra = describeView(view, a), rb = describeView(view, b);
    a.refine.enabled = b.refine.enabled = false;
    const ViewDescriptor pa = describeView(view, a), pb = describeView(view, b);
    const PointSet measured = prepareView(view, refining()).measured;
    const double res = cloudResolution(measured);  // the sensor's spacing: "the same measured point"
    plain_matched += matched(pa.keypoints, pb.keypoints, 0.5 * res);
    refined_matched += matched(ra.keypoints, rb.keypoints, 0.5 * res);
    total += static_cast<int>(ra.keypoints.size());
  }
  RecordProperty("plain", plain_matched);
  RecordProperty("refined", refined_matched);
  RecordProperty("keypoints", total);
  EXPECT_GT(refined_matched, 2 * plain_matched + total / 10) << "plain " << plain_matched << ", refined "
                                                             << refined_matched << " of " << total;
}

TEST(KeypointRefinement, ARigidMotionMovesTheRefinedKeypointsWithTheView) {
  const Cloud view = realCrop("learn10_o1");
  Cloud moved = view;
  const Eigen::Vector3f t(0.004f, -0.002f, 0.003f);
  for (auto& p : moved.points) p += t;
  DescriptorOptions plain = refining();
  plain.refine.enabled = false;
  const auto same = [&](const DescriptorOptions& o) {
    const ViewDescriptor a = describeView(view, o), b = describeView(moved, o);
    EXPECT_EQ(a.keypointCount(), b.keypointCount());
    int n = 0;
    for (std::size_t k = 0; k < a.keypoints.size() && k < b.keypoints.size(); ++k)
      n += (a.keypoints[k] + t - b.keypoints[k]).norm() < 1e-5;
    return std::make_pair(n, static_cast<int>(a.keypoints.size()));
  };
  const auto [refined, k] = same(refining());
  const auto [on_means, k_plain] = same(plain);
  EXPECT_EQ(k, k_plain);
  // A voxel mean moves a little when a point crosses a face under the float rounding of the moved
  // coordinates (the chain's own rigid-motion residue, docs/descriptors.md): refinement adds none.
  // Issue 51: the bound was k - 6, written against one measurement. This move keeps 58 of 64 on every
  // run (the chain is deterministic); 8 moves of this size (0-7 mm per axis, 2026-12-06) keep 56, 58,
  // 58, 58, 58, 59, 61, 61 of 64 on the means, and refinement the same number each time. The bar is
  // this move's own count, not a share of k.
  RecordProperty("moved_with_view", refined);
  RecordProperty("on_means", on_means);
  EXPECT_GE(refined, on_means) << refined << " of " << k << " moved with the view (on the means: " << on_means << ")";
  EXPECT_GE(on_means, 58) << on_means << " of " << k;
}

// The AVX2 scatters (four neighbours at a time, masked) sum in another order than the scalar loop,
// so saliencies may differ in the last bits; on real crops every keypoint lands on the same point.
TEST(KeypointRefinement, TheAvx2ScattersPlaceEveryKeypointAsTheScalarLoopDoes) {
  if (!detail::scatterUsesAvx2()) GTEST_SKIP() << "this CPU has no AVX2: only the scalar loop runs";
  int moved = 0, total = 0;
  for (const char* name : {"learn0_o1", "learn10_o1", "learn34_o2"}) {
    const Cloud view = realCrop(name);
    DescriptorOptions plain = refining();
    plain.refine.enabled = false;
    const ViewDescriptor means = describeView(view, plain);
    const ViewDescriptor simd = describeView(view, refining());
    detail::useScalarScatter(true);
    EXPECT_FALSE(detail::scatterUsesAvx2());
    const ViewDescriptor scalar = describeView(view, refining());
    detail::useScalarScatter(false);
    ASSERT_EQ(simd.keypoints.size(), scalar.keypoints.size()) << name;
    for (std::size_t k = 0; k < simd.keypoints.size(); ++k) {
      EXPECT_EQ(simd.keypoints[k], scalar.keypoints[k]) << name << " keypoint " << k;
      moved += simd.keypoints[k] != means.keypoints[k];
    }
    total += static_cast<int>(simd.keypoints.size());
  }
  EXPECT_GT(2 * moved, total) << "the comparison is empty unless refinement moves most keypoints";
  EXPECT_TRUE(detail::scatterUsesAvx2());
}

TEST(KeypointRefinement, TheRepeatabilityStudyNamesItsDetector) {
  EXPECT_EQ(parseDetector("iss-refined"), Detector::IssRefined);
  EXPECT_EQ(detectorName(Detector::IssRefined), "iss-refined");
}

TEST(KeypointRefinement, NoMeasuredPointsNearLeavesTheKeypointsAsTheyWere) {
  PointSet far;
  for (int i = 0; i < 50; ++i) far.points.emplace_back(1.f + 0.001f * i, 0.f, 0.f);
  const std::vector<Eigen::Vector3f> kp = {Eigen::Vector3f(0, 0, 0), Eigen::Vector3f(0.5f, 0, 0)};
  KeypointRefinementOptions r;
  r.enabled = true;
  EXPECT_EQ(refineKeypointsOnMeasuredPoints(far, kp, 0.003, IssOptions(), r), kp);
  EXPECT_EQ(refineKeypointsOnMeasuredPoints(PointSet(), kp, 0.003, IssOptions(), r), kp);
}

}  // namespace
}  // namespace keyturn
