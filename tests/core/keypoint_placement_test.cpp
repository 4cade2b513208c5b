// Keypoint placement (issue 49): the chain's keypoints, found on voxel means, placed on measured
// points (describe --keypoint-placement nearest|salient).
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>

#include <string>

#include "keyturn/core/cloud_io.h"
#include "keyturn/core/descriptor.h"
#include "keyturn/core/descriptor_parameters.h"
#include "keyturn/core/error.h"
#include "keyturn/core/keypoint_placement.h"
#include "keyturn/core/pose_list.h"
#include "keyturn/studies/repeatability_study.h"

namespace keyturn {
namespace {

Cloud realCrop(const std::string& name) { return loadCloud(std::string(KEYTURN_REAL_DATA) + "/crop/" + name + ".pcd"); }

DescriptorOptions placing(KeypointPlacement p) {
  DescriptorOptions o;
  o.features = {Feature::KPD2, Feature::KPA3};
  o.placement.placement = p;
  return o;
}

TEST(KeypointPlacement, VoxelMeansByDefaultAndTheSpecificationUnchanged) {
  EXPECT_EQ(DescriptorOptions().placement.placement, KeypointPlacement::VoxelMeans);
  EXPECT_EQ(parameterSpec(DescriptorOptions()).count("keypoint_placement"), 0u);  // caches and models keep their names
  DescriptorOptions o;
  descriptorParameter("keypoint_placement").set(o, "salient");
  EXPECT_EQ(o.placement.placement, KeypointPlacement::Salient);
  EXPECT_EQ(parameterSpec(o).at("keypoint_placement"), "salient");
  EXPECT_THROW(descriptorParameter("keypoint_placement").set(o, "centre"), Error);
  EXPECT_EQ(prepareView(realCrop("learn0_o2"), DescriptorOptions()).measured.size(), 0u);
}

// Each placed keypoint is a measured point of the filtered view, distinct, and the chain's choice
// (count and the vertices the geodesics start from) is kept.
TEST(KeypointPlacement, KeypointsLieOnDistinctMeasuredPoints) {
  for (const char* name : {"learn0_o1", "learn10_o1", "learn34_o2"}) {  // each subsampled
    const Cloud view = realCrop(name);
    const ViewDescriptor means = describeView(view, placing(KeypointPlacement::VoxelMeans));
    const PreparedView v = prepareView(view, placing(KeypointPlacement::Salient));
    ASSERT_TRUE(v.working.subsampled) << name;
    int on_measured_before = 0;
    for (const auto& k : means.keypoints)
      for (const auto& p : v.measured.points) on_measured_before += p == k;
    // A voxel of one point has it as its mean; the others' means lie off the measured points.
    EXPECT_LT(on_measured_before, 3 * means.keypointCount() / 4) << name << ": most keypoints sit off measured points";
    for (KeypointPlacement how : {KeypointPlacement::Nearest, KeypointPlacement::Salient}) {
      const ViewDescriptor placed = describeView(view, placing(how));
      ASSERT_EQ(placed.keypointCount(), means.keypointCount()) << name;
      EXPECT_EQ(placed.keypoint_index, means.keypoint_index) << name;
      for (std::size_t k = 0; k < placed.keypoints.size(); ++k) {
        int hits = 0;
        for (const auto& p : v.measured.points) hits += p == placed.keypoints[k];
        EXPECT_GE(hits, 1) << name << " " << keypointPlacementName(how) << " keypoint " << k << " is no measured point";
        for (std::size_t j = 0; j < k; ++j)
          EXPECT_NE(placed.keypoints[j], placed.keypoints[k]) << name << ": keypoints " << j << " and " << k;
      }
    }
  }
}

// "measured" (issue 49) runs ISS itself on the measured points at the working scale: every keypoint
// is a distinct measured point, its geodesics start at a distinct working vertex within a working
// spacing or so of it, and the maxima differ from the chain's (not a placement of its keypoints).
TEST(KeypointPlacement, MeasuredDetectsOnTheMeasuredPointsAndStartsGeodesicsNearby) {
  for (const char* name : {"learn0_o1", "learn34_o2"}) {
    const Cloud view = realCrop(name);
    DescriptorOptions o = placing(KeypointPlacement::Measured);
    o.features = {Feature::KPD2, Feature::GKPD2};
    const PreparedView v = prepareView(view, o);
    ASSERT_TRUE(v.working.subsampled) << name;
    const ViewDescriptor d = describeView(view, o);
    const ViewDescriptor means = describeView(view, placing(KeypointPlacement::VoxelMeans));
    ASSERT_GE(d.keypointCount(), 10) << name;
    ASSERT_EQ(d.keypoint_index.size(), d.keypoints.size()) << name;
    EXPECT_NE(d.keypoint_index, means.keypoint_index) << name;
    for (std::size_t k = 0; k < d.keypoints.size(); ++k) {
      int hits = 0;
      for (const auto& p : v.measured.points) hits += p == d.keypoints[k];
      EXPECT_GE(hits, 1) << name << " keypoint " << k << " is no measured point";
      const Eigen::Vector3f& vertex = v.points.points[static_cast<std::size_t>(d.keypoint_index[k])];
      EXPECT_LT((vertex - d.keypoints[k]).norm(), 2.0 * d.resolution) << name << " keypoint " << k;
      for (std::size_t j = 0; j < k; ++j) EXPECT_NE(d.keypoint_index[j], d.keypoint_index[k]) << name;
    }
  }
}

// What the placement is for: on the full-resolution Stanford scans (docs/repeatability.md) the salient
// measured points repeat at the sensor's precision where voxel means do not. The four decimated scans
// shipped here are too coarse for it (raw spacing 1.19 mm, 0.4 × the working spacing): there the
// voxel means repeat better (iss-chain 0.148 against iss-salient 0.124 at ε = 1 × resolution, all
// pairs). This test pins that measured behaviour, so a change that makes placement help (or hurt
// more) on coarse scans shows up.
TEST(KeypointPlacement, OnTheDecimatedRealScansTheVoxelMeansStillRepeatBetter) {
  const std::string conf = std::string(KEYTURN_REAL_DATA) + "/../../stanford-bunny-decimated/bun.conf";
  std::vector<StudyView> views;
  for (const PoseListEntry& e : readPoses(conf)) views.push_back({e.file, "bunny", std::nan(""), e.world_from_view.inverse()});
  StudyOptions o;
  o.detectors = {Detector::IssChain, Detector::IssSalient};
  o.eps_res = {1.0, 3.0};
  o.keypoints = 60;
  o.pairs = parsePairRule("all-within:180");
  const Study st = runRepeatabilityStudy(views, o);
  const auto& chain = st.detectors.at(Detector::IssChain).relative_equal;
  const auto& salient = st.detectors.at(Detector::IssSalient).relative_equal;
  RecordProperty("iss_chain_rel_at_3", std::to_string(chain[1]));
  RecordProperty("iss_salient_rel_at_3", std::to_string(salient[1]));
  EXPECT_GT(salient[0], 0.08) << "iss-salient at 1 × resolution";
  EXPECT_GT(chain[1], salient[1]) << "iss-chain " << chain[1] << " against iss-salient " << salient[1] << " at 3 ×";
}

}  // namespace
}  // namespace keyturn
