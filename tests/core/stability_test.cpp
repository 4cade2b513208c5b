// The perturbations of the stability study do what they are named for, and the chain's
// description of a real or simulated view does not move when the view moves rigidly
// (issue 30: the working resolution's grid anchored to the object, not the camera).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "keyturn/core/cloud_io.h"
#include "keyturn/core/error.h"
#include "keyturn/studies/stability_study.h"
#include "keyturn/studies/view_perturbation.h"
#include "keyturn/sim/tof_view.h"

namespace keyturn {
namespace {

Cloud realCrop(const std::string& name) { return loadCloud(std::string(KEYTURN_REAL_DATA) + "/crop/" + name + ".pcd"); }

Perturbation named(const std::string& name) { return perturbationsNamed(name).front(); }

Eigen::Vector3d centroidOf(const Cloud& c) {
  Eigen::Vector3d s = Eigen::Vector3d::Zero();
  std::size_t n = 0;
  for (const auto& p : c.points)
    if (Cloud::isValid(p)) s += p.cast<double>(), ++n;
  return s / static_cast<double>(n);
}

TEST(ViewPerturbation, RigidMotionsMoveEveryPointAsNamed) {
  const Cloud view = realCrop("learn0_o2");
  const Cloud moved = *perturbView(view, named("translate-5mm"), 3);
  for (std::size_t i = 0; i < view.size(); i += 97)
    EXPECT_NEAR((moved.points[i] - view.points[i]).norm(), 0.005, 1e-6);
  const Cloud turned = *perturbView(view, named("rotate-centroid-10deg"), 3);
  EXPECT_LT((centroidOf(turned) - centroidOf(view)).norm(), 1e-6);
  const Eigen::Vector3f a = view.points[0] - view.points[500], b = turned.points[0] - turned.points[500];
  EXPECT_NEAR(a.norm(), b.norm(), 1e-6);
  EXPECT_NEAR(std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.f, 1.f)) * 180 / M_PI, 10.0, 10.0);
  const Cloud about_camera = *perturbView(view, named("rotate-camera-2deg"), 3);
  for (std::size_t i = 0; i < view.size(); i += 97) EXPECT_NEAR(about_camera.points[i].norm(), view.points[i].norm(), 1e-6);
  EXPECT_GT((about_camera.points[0] - view.points[0]).norm(), 1e-3);  // ~2° at ~0.8 m moves ~2.8 cm at most
}

TEST(ViewPerturbation, ResamplingNoiseAndRoundingAreWhatTheySay) {
  const Cloud view = realCrop("learn0_o2");
  const Cloud dropped = *perturbView(view, named("drop-10pct"), 5);
  EXPECT_NEAR(static_cast<double>(dropped.size()) / view.size(), 0.9, 0.03);
  EXPECT_FALSE(perturbView(view, named("shift-mask-1px"), 5).has_value());  // no pixels to move

  const Cloud jittered = *perturbView(view, named("jitter-0.1mm"), 5);
  double ss = 0;
  for (std::size_t i = 0; i < view.size(); ++i) ss += (jittered.points[i] - view.points[i]).squaredNorm();
  EXPECT_NEAR(std::sqrt(ss / view.size() / 3), 1e-4, 1e-5);

  const Cloud noisy = *perturbView(view, named("sensor-noise"), 5);
  double moved = 0;
  for (std::size_t i = 0; i < view.size(); ++i) {
    EXPECT_LT(noisy.points[i].normalized().cross(view.points[i].normalized()).norm(), 1e-5);  // on its own ray
    moved += std::abs(noisy.points[i].z() - view.points[i].z());
  }
  EXPECT_GT(moved / view.size(), 5e-4);  // σ ≈ 1.3 mm at ~0.8 m

  const Cloud rounded = *perturbView(view, named("depth-round-1mm"), 5);
  for (std::size_t i = 0; i < view.size(); i += 31)
    EXPECT_NEAR(rounded.points[i].z() * 1000, std::round(rounded.points[i].z() * 1000), 1e-3);
}

TEST(ViewPerturbation, AMaskShiftOnlyTakesPixelsAway) {
  Cloud frame = loadCloud(std::string(KEYTURN_REAL_DATA) + "/masked/learn0_o1.pcd");
  const Cloud shifted = *perturbView(frame, named("shift-mask-1px"), 2);
  ASSERT_EQ(shifted.size(), frame.size());
  std::size_t lost = 0;
  for (std::size_t i = 0; i < frame.size(); ++i) {
    if (Cloud::isValid(shifted.points[i])) EXPECT_EQ(shifted.points[i], frame.points[i]);
    else lost += Cloud::isValid(frame.points[i]);
  }
  EXPECT_GT(lost, 20u);                        // one edge row or column of the object
  EXPECT_LT(lost, frame.validCount() / 5);
}

std::vector<StabilityView> rigidStudyViews() {
  std::vector<StabilityView> views;
  for (const char* name : {"learn0_o1", "learn8_o2", "learn34_o1", "learn43_o3"})  // boxes and cylinders
    views.push_back({name, name, realCrop(name)});
  return views;
}

// The six keypoint functions under `perturbations`, two draws each, without PCL's descriptors.
StabilityStudy keypointStudy(DescriptorOptions descriptor, const std::vector<StabilityView>& views,
                             std::vector<Perturbation> perturbations) {
  StabilityOptions o;
  o.descriptor = std::move(descriptor);
  o.descriptor.features = {Feature::KPD2, Feature::KPD3, Feature::KPA3, Feature::GKPD1, Feature::GKPD2, Feature::GKPCD2};
  o.perturbations = std::move(perturbations);
  o.repetitions = 2;
  o.pcl_descriptors = false;
  return runStabilityStudy(views, o);
}

DescriptorOptions withSmoothing(double sigma) {
  DescriptorOptions o;
  o.histogram.smoothing = sigma;
  return o;
}

StabilityStudy rigidStudy(const WorkingResolutionOptions& working, std::vector<StabilityView> views,
                          const std::string& motions = "rigid", bool fill_budget = DescriptorOptions().iss.fill_budget) {
  DescriptorOptions d;
  d.working = working;
  d.iss.fill_budget = fill_budget;
  std::vector<Perturbation> perturbations;
  for (const char* name : {"rotate-camera-2deg", "rotate-camera-10deg"})
    if (motions == "about-camera") perturbations.push_back(named(name));
  if (motions == "rigid") perturbations = perturbationsNamed("rigid");
  return keypointStudy(d, views, perturbations);
}

// Issue 30's target: a rigid motion moves no keypoint function's PDF by more than L1 0.01 and
// changes no keypoint count, on real Kinect crops (unorganized: no step sees the camera).
TEST(Stability, RigidMotionLeavesEveryKeypointFunctionAsItWas) {
  const StabilityStudy s = rigidStudy(WorkingResolutionOptions(), rigidStudyViews());
  ASSERT_TRUE(s.errors.empty()) << s.errors.front();
  EXPECT_EQ(s.maxAbsKeypointChange(true), 0);
  // GKPCD2's PCA normals differ in the last bits after a motion, and a curvature cost that close
  // to a tie can pick another path: with unsmoothed PDFs it moved by up to L1 0.03 here (below).
  for (const auto& f : s.functions) EXPECT_LE(f.rigidMaxL1(), 0.01) << f.name;
  // The contrast at the budget it was measured at (64): with 128 keypoints a path that flips moves a
  // quarter of the mass it moved, and the raw GKPCD2 sits at 0.0095 (clang) to just over 0.01 (gcc).
  DescriptorOptions unsmoothed = withSmoothing(0.0);
  unsmoothed.iss.max_keypoints = 64;
  const StabilityStudy raw = keypointStudy(unsmoothed, rigidStudyViews(), perturbationsNamed("rigid"));
  const FunctionStability& gkpcd2 = raw.functions.back();
  ASSERT_EQ(gkpcd2.name, "gkpcd2");
  EXPECT_GT(gkpcd2.rigidMaxL1(), 0.01);
  EXPECT_LE(gkpcd2.rigidMaxL1(), 0.05);
}

// A real masked frame and a simulated SR4000 frame turned about the camera (their rays, and so
// the jump edges and the support's camera side, stay as they were; moved otherwise, the frame
// steps that see the camera may decide otherwise, as a camera seeing it so would).
TEST(Stability, AFrameTurnedAboutTheCameraIsDescribedAsItWas) {
  const Cloud masked = loadCloud(std::string(KEYTURN_REAL_DATA) + "/masked/learn34_o2.pcd");
  const StabilityStudy s = rigidStudy(WorkingResolutionOptions(),
                                      {{"masked", "masked", masked}, {"builtin:mug", "builtin:mug", sim::builtinBenchmarkView()},
                                       {"crop", "crop", realCrop("learn0_o2")}}, "about-camera");
  EXPECT_EQ(s.maxAbsKeypointChange(true), 0);
  for (const auto& f : s.functions) EXPECT_LE(f.rigidMaxL1(), 0.01) << f.name;
}

// The grids of before: anchored to the camera, or thinned nearest points in index order (whose
// greedy decisions cascade from a rounding-level difference), the description moves with the view —
// what the tests above would catch if either came back.
TEST(Stability, TheCameraAnchoredOrThinnedGridMovesWithTheView) {
  WorkingResolutionOptions camera;
  camera.anchor = VoxelAnchor::CameraGrid;
  camera.points = VoxelPoints::Thinned;
  WorkingResolutionOptions thinned;
  thinned.points = VoxelPoints::Thinned;
  for (const auto& working : {camera, thinned}) {
    // K capped, not filled: a filled budget would hide the grid's moving maxima behind K = 64.
    const StabilityStudy s = rigidStudy(working, rigidStudyViews(), "rigid", false);
    double worst = 0;
    for (const auto& f : s.functions) worst = std::max(worst, f.rigidMaxL1());
    EXPECT_GT(worst, 0.05) << voxelAnchorName(working.anchor);
      EXPECT_GT(s.maxAbsKeypointChange(true), 0) << voxelAnchorName(working.anchor);
  }
}

// Issue 49's target, K steady under 0.1 mm jitter: on four real crops where ISS finds fewer local
// maxima than the budget (18–44), jitter moves their count by up to 6 (measured: `keyturn stability`);
// the filled budget (the default since 2026-12-07; `--fill-budget off` caps) keeps K at the budget.
TEST(Stability, AFilledBudgetKeepsKUnderJitter) {
  std::vector<StabilityView> views;
  for (const char* name : {"learn0_o2", "learn14_o2", "learn43_o1", "learn41_o1"}) views.push_back({name, name, realCrop(name)});
  DescriptorOptions capped;
  capped.iss.fill_budget = false;
  EXPECT_GT(keypointStudy(capped, views, {named("jitter-0.1mm")}).maxAbsKeypointChangeUnder("jitter-0.1mm"), 2);
  const DescriptorOptions fill;
  ASSERT_TRUE(fill.iss.fill_budget);
  const StabilityStudy filled = keypointStudy(fill, views, {named("jitter-0.1mm")});
  ASSERT_TRUE(filled.errors.empty()) << filled.errors.front();
  EXPECT_EQ(filled.maxAbsKeypointChangeUnder("jitter-0.1mm"), 0);
}

// Kernel density PDFs (pdf_smoothing): on real crops jittered far below the sensor's noise or
// given its noise, every length function moves less in units of the distance between views, and
// the two least steady (GKPD1, GKPCD2: 64 values, curvature-picked paths) by at least a fifth;
// KPA3's angles stay as binned.
TEST(Stability, SmoothedPdfsMoveLessUnderNoiseThanTheDistanceBetweenViews) {
  const auto study = [](double sigma) {
    return keypointStudy(withSmoothing(sigma), rigidStudyViews(), {named("jitter-0.1mm"), named("sensor-noise")});
  };
  const StabilityStudy hard = study(0.0), smooth = study(1.5);
  ASSERT_EQ(hard.functions.size(), smooth.functions.size());
  for (std::size_t f = 0; f < hard.functions.size(); ++f) {
    const std::string& name = hard.functions[f].name;
    const double before = hard.functions[f].ratioOverall(), after = smooth.functions[f].ratioOverall();
    if (name == "kpa3") {
      EXPECT_EQ(after, before);
      continue;
    }
    EXPECT_LT(after, before) << name;
    if (name == "gkpd1" || name == "gkpcd2") EXPECT_LT(after, 0.8 * before) << name;
  }
}

TEST(Stability, ReportsRatiosAgainstTheDistanceBetweenViews) {
  StabilityOptions o;
  o.descriptor.features = {Feature::KPD2, Feature::D2};
  o.descriptor.scaled_twin = true;
  o.perturbations = {named("jitter-0.1mm"), named("translate-1mm")};
  o.repetitions = 1;
  std::vector<StabilityView> views = {{"a", "a", realCrop("learn0_o1")}, {"b", "b", realCrop("learn34_o1")},
                                      {"c", "c", realCrop("learn8_o2")}};
  const StabilityStudy s = runStabilityStudy(views, o);
  ASSERT_EQ(s.functions.size(), 2u + 2u + 2u);  // kpd2, d2, s_kpd2, s_d2, esf, vfh
  for (const auto& f : s.functions) {
    EXPECT_EQ(f.between_l1.size(), 3u) << f.name;
    EXPECT_GT(f.betweenMedianL1(), 0.0) << f.name;
    EXPECT_EQ(f.l1[0].size(), 3u) << f.name;
    EXPECT_NEAR(f.ratio(0), f.medianL1(0) / f.betweenMedianL1(), 1e-12);
  }
  EXPECT_NE(stabilityMarkdown(s, "test").find("| esf |"), std::string::npos);
  // Two views of one group give no between-view pair.
  views[1].group = "a";
  views[2].group = "a";
  const StabilityStudy same = runStabilityStudy(views, o);
  EXPECT_TRUE(same.functions.front().between_l1.empty());
  EXPECT_TRUE(std::isnan(same.functions.front().betweenMedianL1()));
}

// Issue 47: the study's ESF is the figure PCL gives on the cloud the user has. On an object cut
// jittered far below the sensor's noise, PCL's seeded ESF of the given cloud draws the same
// samples and barely moves; computed after keyturn's filter, whose outlier step keeps another
// count of points, every sample index shifts and ESF moves by its sampling noise.
TEST(Stability, PclDescriptorsDescribeTheCloudAsGiven) {
  StabilityOptions o;
  o.descriptor.features = {Feature::KPD2};
  o.descriptor.scaled_twin = false;
  o.perturbations = {named("jitter-0.1mm")};
  o.repetitions = 1;
  const std::vector<StabilityView> views = {{"a", "a", realCrop("learn0_o1")}, {"b", "b", realCrop("learn34_o1")},
                                            {"c", "c", realCrop("learn8_o2")}, {"d", "d", realCrop("learn40_o2")}};
  const auto esfRatio = [&](PclInput input) {
    o.pcl_input = input;
    const StabilityStudy s = runStabilityStudy(views, o);
    EXPECT_EQ(s.pcl_input, input);
    const auto esf = std::find_if(s.functions.begin(), s.functions.end(), [](const auto& f) { return f.name == "esf"; });
    EXPECT_NE(esf, s.functions.end());
    EXPECT_NE(stabilityMarkdown(s, "t").find("jitter-0.1mm ratio |"), std::string::npos);
    EXPECT_EQ(s.maxAbsKeypointChangeUnder("jitter-0.1mm"), s.maxAbsKeypointChange(false));
    EXPECT_EQ(s.maxAbsKeypointChangeUnder("wobble"), -1);
    return esf == s.functions.end() ? std::nan("") : esf->ratio(0);
  };
  const double given = esfRatio(PclInput::Given), filtered = esfRatio(PclInput::Filtered);
  EXPECT_LT(given, 0.08);
  EXPECT_GT(filtered, 2 * given);
  EXPECT_EQ(pclInputNamed("filtered"), PclInput::Filtered);
  EXPECT_THROW(pclInputNamed("raw"), Error);
}

TEST(Stability, NamesWhatItCannotStudy) {
  EXPECT_THROW(perturbationsNamed("wobble"), Error);
  StabilityOptions o;
  o.repetitions = 1;
  Cloud empty;
  std::vector<StabilityView> views = {{"empty", "x", empty}, {"a", "a", realCrop("learn0_o1")}};
  try {
    runStabilityStudy(views, o);
    FAIL() << "one describable view is not a study";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("empty"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace keyturn
