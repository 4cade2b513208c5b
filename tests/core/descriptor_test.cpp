#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "keyturn/core/descriptor.h"
#include "keyturn/core/error.h"
#include "keyturn/core/filter.h"
#include "keyturn/sim/tof_view.h"
#include "support/synthetic_clouds.h"

using namespace keyturn;

namespace {
Cloud mugView(double angle) {
  sim::TofViewRenderer r(sim::makeMugMesh());
  sim::SceneView v;
  v.turntable_deg = angle;
  return r.render(v);
}

std::string errorOf(const Cloud& c, const DescriptorOptions& o) {
  try {
    describeView(c, o);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(Descriptor, MugViewGivesNormalisedPdfsAndAKeypointCount) {
  DescriptorOptions o;
  o.features = allFeatures();
  const ViewDescriptor d = describeView(mugView(0), o);
  EXPECT_GT(d.input_points, 15000u);             // table + mug
  EXPECT_LT(d.points, d.input_points / 5);        // table removed
  EXPECT_GT(d.points, 500u);
  EXPECT_GE(d.keypointCount(), 10);
  EXPECT_NEAR(d.resolution, 0.002, 0.001);        // ~2 mm at 0.45 m
  ASSERT_EQ(d.pdfs.size(), allFeatures().size());
  for (const auto& pdf : d.pdfs) {
    ASSERT_EQ(pdf.size(), 32u);
    EXPECT_NEAR(std::accumulate(pdf.begin(), pdf.end(), 0.0), 1.0, 1e-9);
  }
  EXPECT_EQ(d.featureVector().size(), 32u * allFeatures().size());
  // The inside of the mug meets the outside only along a rim about one pixel
  // wide, so some keypoints may sit in another component: counted, never binned.
  EXPECT_LE(d.unreachable_pairs, d.keypointCount() * (d.keypointCount() - 1) / 2);
  EXPECT_LE(d.unreachable_keypoints, d.keypointCount());
}

TEST(Descriptor, ConnectedSurfaceHasEveryPairReachable) {
  DescriptorOptions o;
  o.filter = false;
  const auto d = describeView(test::unorganized(test::cubeSurface(0.1f, 21, Eigen::Vector3f(0, 0, 1))), o);
  EXPECT_EQ(d.keypointCount(), 8);
  EXPECT_EQ(d.unreachable_pairs, 0);
  EXPECT_EQ(d.unreachable_keypoints, 0);
  // 28 pairs of cube corners: 12 edges (0.1 m), 12 face diagonals, 4 space
  // diagonals; their geodesics are ≥ the Euclidean distances, so GKPD2's mass
  // sits at or right of KPD2's.
  const auto& kpd2 = d.pdfs[0];
  const auto& gkpd2 = d.pdfs[4];
  double mean_e = 0, mean_g = 0;
  const double w_e = 0.35 / 32, w_g = 1.5 * 0.35 / 32;
  for (int b = 0; b < 32; ++b) {
    mean_e += kpd2[b] * (b + 0.5) * w_e;
    mean_g += gkpd2[b] * (b + 0.5) * w_g;
  }
  EXPECT_GT(mean_g, mean_e);
}

TEST(Descriptor, SameViewSameDescriptor) {
  DescriptorOptions o;
  const Cloud c = mugView(40);
  EXPECT_EQ(describeView(c, o).featureVector(), describeView(c, o).featureVector());
}

TEST(Descriptor, FilteredPointsGiveTheSameDescriptorAsTheWholeChain) {
  DescriptorOptions o;
  o.features = {Feature::KPD2, Feature::KPA3, Feature::GKPD2, Feature::D2};
  const Cloud c = mugView(40);
  const ViewDescriptor whole = describeView(c, o);
  const PointSet filtered = PointSet::fromCloud(filterCloud(c, o.filter_options));
  const ViewDescriptor part = describeFilteredPoints(filtered, o);
  EXPECT_EQ(part.points, whole.points);
  EXPECT_EQ(part.input_points, filtered.size());  // only the filtered points were seen
  EXPECT_GT(whole.input_points, whole.points);
  EXPECT_EQ(part.keypoint_index, whole.keypoint_index);
  EXPECT_EQ(part.featureVector(), whole.featureVector());
  EXPECT_EQ(part.times.filter, 0.0);
  EXPECT_GT(whole.times.filter, 0.0);
  PointSet two;
  two.points = {Eigen::Vector3f(0, 0, 1), Eigen::Vector3f(0, 0.01f, 1)};
  try {
    describeFilteredPoints(two, o);
    ADD_FAILURE() << "two points were described";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("only 2 points left after filtering"), std::string::npos) << e.what();
  }
}

TEST(Descriptor, EmptyAndAllNaNCloudsAreClearErrors) {
  DescriptorOptions o;
  EXPECT_NE(errorOf(Cloud(), o).find("empty point cloud"), std::string::npos);
  Cloud nan = test::organizedPlanes(10, 10, 10.f, 1.f, 1.f, 0, 0, 0, 0);
  for (auto& p : nan.points) p.setConstant(NAN);
  EXPECT_NE(errorOf(nan, o).find("no valid points"), std::string::npos);
}

TEST(Descriptor, TooFewKeypointsIsAnError) {
  DescriptorOptions o;
  o.filter = false;
  const Cloud plane = test::organizedPlanes(30, 30, 100.f, 1.f, 1.f, 0, 0, 0, 0);
  const std::string msg = errorOf(plane, o);
  EXPECT_NE(msg.find("too few keypoints: ISS found 0"), std::string::npos) << msg;
}

TEST(Descriptor, PerViewRangeIsScaleInvariant) {
  DescriptorOptions o;
  o.filter = false;
  o.features = {Feature::KPD2, Feature::KPA3};
  o.histogram.mode = RangeMode::PerView;
  const auto cube = test::cubeSurface(0.1f, 21, Eigen::Vector3f(0, 0, 1));
  std::vector<Eigen::Vector3f> big;
  for (const auto& p : cube) big.push_back(2.f * p);
  const auto a = describeView(test::unorganized(cube), o);
  const auto b = describeView(test::unorganized(big), o);
  ASSERT_EQ(a.keypointCount(), b.keypointCount());
  for (std::size_t i = 0; i < a.pdfs[0].size(); ++i) EXPECT_NEAR(a.pdfs[0][i], b.pdfs[0][i], 1e-9);
  // With the fixed metric range the doubled cube moves mass to longer bins.
  o.histogram.mode = RangeMode::Fixed;
  EXPECT_NE(describeView(test::unorganized(cube), o).pdfs[0], describeView(test::unorganized(big), o).pdfs[0]);
}
