#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <filesystem>
#include <fstream>
#include <random>

#include "keyturn/core/error.h"
#include "keyturn/core/keypoint_detectors.h"
#include "keyturn/core/pose_list.h"
#include "keyturn/core/radius_search.h"
#include "keyturn/core/repeatability.h"
#include "keyturn/studies/repeatability_study.h"
#include "support/error_of.h"
#include "support/synthetic_clouds.h"

using namespace keyturn;
using keyturn::test::errorOf;

namespace {
Eigen::Matrix4d transform(double deg, const Eigen::Vector3d& axis, const Eigen::Vector3d& t) {
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.topLeftCorner<3, 3>() = Eigen::AngleAxisd(deg * M_PI / 180, axis.normalized()).toRotationMatrix();
  T.topRightCorner<3, 1>() = t;
  return T;
}

PointSet moved(const std::vector<Eigen::Vector3f>& pts, const Eigen::Matrix4d& T, float noise = 0, unsigned seed = 1) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> g(0.f, noise > 0 ? noise : 1.f);
  std::vector<Eigen::Vector3f> out;
  for (const auto& p : pts) {
    Eigen::Vector3f q = (T * p.cast<double>().homogeneous()).head<3>().cast<float>();
    if (noise > 0) q += Eigen::Vector3f(g(rng), g(rng), g(rng));
    out.push_back(q);
  }
  return PointSet::fromCloud(test::unorganized(out));
}

// A lobed blob sampled at random: no symmetry for ICP to slide along and no
// saliency plateaus (a box's straight edges have equal λ3 all along, so float
// rounding under a rotation alone changes which edge point wins suppression).
std::vector<Eigen::Vector3f> object() {
  std::mt19937 rng(5);
  std::normal_distribution<float> g(0.f, 1.f);
  std::vector<Eigen::Vector3f> pts;
  for (int i = 0; i < 6000; ++i) {
    const Eigen::Vector3f d = Eigen::Vector3f(g(rng), g(rng), g(rng)).normalized();
    const float r = 0.05f * (1.f + 0.25f * std::sin(3 * d.x() + 1) * std::cos(2 * d.y()) + 0.15f * d.z() * d.z() * d.x());
    pts.push_back(r * d + Eigen::Vector3f(0, 0, 1));
  }
  return pts;
}
}  // namespace

TEST(Repeatability, AnExactCopyUnderAKnownTransformRepeatsFully) {
  const auto pts = object();
  const PointSet model = PointSet::fromCloud(test::unorganized(pts));
  const Eigen::Matrix4d T = transform(25, {0.3, 1, 0.2}, {0.05, -0.02, 0.1});
  const PointSet scene = moved(pts, T);
  const double res = cloudResolution(model);
  for (Detector d : {Detector::Iss, Detector::Harris3d, Detector::Sift3d, Detector::Uniform}) {
    const auto km = detectKeypoints(d, model, res), ks = detectKeypoints(d, scene, res);
    ASSERT_GT(km.size(), 5u) << detectorName(d);
    const auto r = keypointRepeatability(km, ks, scene, res, T, {0.25 * res, 1.0 * res, 3.0 * res});
    // Every keypoint on the surface is visible in a full copy; PCL's SIFT places
    // keypoints at voxel-grid positions of its scale space, a few off the surface.
    if (d == Detector::Sift3d) EXPECT_GT(r.visible, 0.8 * r.model_keypoints);
    else EXPECT_EQ(r.visible, r.model_keypoints) << detectorName(d);
    // keyturn's ISS is deterministic and rotation invariant: the same keypoints.
    if (d == Detector::Iss) EXPECT_DOUBLE_EQ(r.relative[1], 1.0);
    // PCL's Harris and uniform sampling's voxel grid are not exactly rotation invariant.
    else if (d == Detector::Harris3d) EXPECT_GT(r.relative[1], 0.9);
    EXPECT_GE(r.relative[2], r.relative[1]) << detectorName(d);
  }
}

TEST(Repeatability, NoiseLowersItMonotonicallyOnAverage) {
  const auto pts = object();
  const PointSet model = PointSet::fromCloud(test::unorganized(pts));
  const double res = cloudResolution(model);
  const auto km = detectKeypoints(Detector::Iss, model, res);
  const Eigen::Matrix4d T = transform(10, {0, 1, 0}, {0.01, 0, 0});
  std::vector<double> mean;
  for (double sigma : {0.0, 0.15, 0.4}) {
    double sum = 0;
    for (unsigned seed = 1; seed <= 4; ++seed) {
      const PointSet scene = moved(pts, T, static_cast<float>(sigma * res), seed);
      const auto r = keypointRepeatability(km, detectKeypoints(Detector::Iss, scene, res), scene, res, T, {1.0 * res});
      sum += r.relative[0];
    }
    mean.push_back(sum / 4);
  }
  EXPECT_DOUBLE_EQ(mean[0], 1.0);
  EXPECT_GT(mean[0], mean[1]);
  EXPECT_GT(mean[1], mean[2]);
}

TEST(Repeatability, KeypointsOffTheSceneSurfaceAreNotCounted) {
  const auto pts = object();
  const PointSet model = PointSet::fromCloud(test::unorganized(pts));
  const double res = cloudResolution(model);
  const auto km = detectKeypoints(Detector::Iss, model, res);
  // The scene sees only the half with x < 0: the other half is occluded.
  std::vector<Eigen::Vector3f> half;
  for (const auto& p : pts)
    if (p.x() < 0) half.push_back(p);
  const PointSet scene = PointSet::fromCloud(test::unorganized(half));
  // Visible by definition: a scene point within 1 × resolution.
  int expected = 0, far_side = 0;
  for (const auto& k : km) {
    float best = 1e9f;
    for (const auto& p : half) best = std::min(best, (p - k).norm());
    expected += best <= res ? 1 : 0;
    far_side += k.x() > res ? 1 : 0;
  }
  const auto r = keypointRepeatability(km, detectKeypoints(Detector::Iss, scene, res), scene, res,
                                       Eigen::Matrix4d::Identity(), {2.0 * res});
  EXPECT_EQ(r.visible, expected);
  EXPECT_LE(r.visible, r.model_keypoints - far_side);  // none from the occluded half
  EXPECT_GT(far_side, 10);
}

TEST(Repeatability, IcpRecoversAPerturbedGroundTruth) {
  const auto pts = object();
  const PointSet model = PointSet::fromCloud(test::unorganized(pts));
  const Eigen::Matrix4d T = transform(20, {0, 0, 1}, {0.02, 0.01, 0});
  const PointSet scene = moved(pts, T);
  // 2° and 5 mm off, about the object's own centre (it stands 1 m from the origin).
  Eigen::Matrix4d to_centre = Eigen::Matrix4d::Identity(), back = Eigen::Matrix4d::Identity();
  const Eigen::Vector3d c = (T * Eigen::Vector4d(0, 0, 1, 1)).head<3>();
  to_centre.topRightCorner<3, 1>() = -c;
  back.topRightCorner<3, 1>() = c;
  const Eigen::Matrix4d guess = back * transform(2, {1, 1, 0}, {0.004, -0.003, 0.002}) * to_centre * T;
  const double res = cloudResolution(model);
  const auto icp = refineByIcp(model, scene, guess, 6 * res);
  EXPECT_TRUE(icp.converged);
  const Eigen::Matrix4d err = icp.scene_from_model * T.inverse();
  const Eigen::Vector3d dt = err.topRightCorner<3, 1>();
  const Eigen::Matrix3d dR = err.topLeftCorner<3, 3>();
  EXPECT_LT(dt.norm(), 0.0005);
  EXPECT_LT(Eigen::AngleAxisd(dR).angle() * 180 / M_PI, 0.2);
  EXPECT_LT(icp.rms_m, 0.2 * res);
}

TEST(Repeatability, AnEqualBudgetGivesEachDetectorExactlyK) {
  const auto pts = object();
  const PointSet set = PointSet::fromCloud(test::unorganized(pts));
  const double res = cloudResolution(set);
  for (Detector d : {Detector::Iss, Detector::Harris3d, Detector::Sift3d, Detector::Uniform}) {
    const auto native_kp = detectKeypoints(d, set, res);
    const std::size_t native = native_kp.size();
    for (std::size_t i = 0; i < native; ++i)  // SIFT finds some points at two scales: one location, one keypoint
      for (std::size_t j = i + 1; j < native; ++j) ASSERT_GT((native_kp[i] - native_kp[j]).norm(), 0.f) << detectorName(d) << " native";
    // Below, at and above the detector's own count: cut to its most salient, or completed.
    for (std::size_t k : {std::size_t{5}, native, native + 40}) {
      const auto kp = detectKeypointsAtBudget(d, set, res, static_cast<int>(k));
      EXPECT_EQ(kp.size(), k) << detectorName(d) << " native " << native;
      for (std::size_t i = 0; i < kp.size(); ++i)
        for (std::size_t j = i + 1; j < kp.size(); ++j) ASSERT_GT((kp[i] - kp[j]).norm(), 0.f) << detectorName(d) << " K " << k << ": point " << j << " repeats point " << i;
    }
    EXPECT_EQ(detectKeypointsAtBudget(d, set, res, static_cast<int>(set.size()) + 10).size(), set.size());
  }
  // ISS's K most salient are its own keypoints: at its native count the budget changes nothing.
  const auto iss = detectKeypoints(Detector::Iss, set, res);
  auto budget = detectKeypointsAtBudget(Detector::Iss, set, res, static_cast<int>(iss.size()));
  const auto less = [](const Eigen::Vector3f& a, const Eigen::Vector3f& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  };
  auto sorted = iss;
  std::sort(sorted.begin(), sorted.end(), less);
  std::sort(budget.begin(), budget.end(), less);
  EXPECT_EQ(sorted, budget);
}

TEST(Repeatability, PairRulesReadAndWriteTheirText) {
  EXPECT_EQ(parsePairRule("consecutive").kind, PairRule::Kind::Consecutive);
  EXPECT_EQ(parsePairRule("from-first").kind, PairRule::Kind::FromFirst);
  const PairRule within = parsePairRule("all-within:45");
  EXPECT_EQ(within.kind, PairRule::Kind::AllWithin);
  EXPECT_EQ(within.within_deg, 45);
  for (const char* t : {"consecutive", "from-first", "all-within:45", "all-within:22.5"})
    EXPECT_EQ(pairRuleName(parsePairRule(t)), t);
  // Errors name the rule as given, never an option of a front end.
  EXPECT_EQ(errorOf([] { parsePairRule("x"); }), "pair rule 'x': expected consecutive, from-first or all-within:DEG");
  EXPECT_EQ(errorOf([] { parsePairRule("all-within:ten"); }), "pair rule 'all-within:ten': all-within needs degrees (0 or more)");
  EXPECT_EQ(errorOf([] { parsePairRule("all-within:-5"); }), "pair rule 'all-within:-5': all-within needs degrees (0 or more)");
  // Each rule's pairs among four views 30° apart, given out of order.
  std::vector<StudyView> v(4);
  for (int i = 0; i < 4; ++i) v[i] = StudyView{"v" + std::to_string(i), "g", 30.0 * ((i + 2) % 4)};  // 60, 90, 0, 30
  using P = std::vector<std::pair<int, int>>;
  EXPECT_EQ(selectPairs(v, parsePairRule("consecutive")), (P{{2, 3}, {3, 0}, {0, 1}}));
  EXPECT_EQ(selectPairs(v, parsePairRule("from-first")), (P{{2, 3}, {2, 0}, {2, 1}}));
  EXPECT_EQ(selectPairs(v, parsePairRule("all-within:60")).size(), 5u);  // all but 0° with 90°
}

TEST(Repeatability, EachEpsMustBeAPositiveMultipleOfTheResolution) {
  StudyOptions o;
  o.eps_res = {1, -0.5};
  // Checked before any view is read (these files do not exist).
  EXPECT_EQ(errorOf([&] { runRepeatabilityStudy({StudyView{"a.pcd", "g"}, StudyView{"b.pcd", "g"}}, o); }),
            "ε -0.5: must be a positive multiple of the resolution");
}
