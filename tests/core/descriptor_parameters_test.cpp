#include "keyturn/core/descriptor_parameters.h"

#include <gtest/gtest.h>

#include <set>

#include "keyturn/core/error.h"

using namespace keyturn;

namespace {

const DescriptorParameter& row(const std::string& flag) {
  for (const auto& p : descriptorParameters())
    if (p.flag == flag) return p;
  throw std::runtime_error("no row " + flag);
}

// A value other than the default that the row accepts.
std::string otherValue(const DescriptorParameter& p, const DescriptorOptions& d) {
  switch (p.kind) {
    case DescriptorParameter::Kind::Switch: return p.get(d) == "on" ? "off" : "on";
    case DescriptorParameter::Kind::Choice: {
      const std::string now = p.get(d);
      if (p.flag == "--range") return now == "fixed" ? "per-view" : "fixed";
      if (p.flag == "--binning") return now == "hard" ? "linear" : "hard";
      if (p.flag == "--voxel-grid") return now == "object" ? "camera" : "object";
      if (p.flag == "--voxel-points") return now == "means" ? "thinned" : "means";
      ADD_FAILURE() << "no other value known for " << p.flag;
      return now;
    }
    case DescriptorParameter::Kind::Integer: return std::to_string(std::stoll(p.get(d)) + 3);
    case DescriptorParameter::Kind::Number: return p.flag == "--budget-taper" ? "0.25" : "1.25";
  }
  return "";
}

}  // namespace

// The specification of the default options, as feature caches and models of cache version 4 hold
// it (version 3 added the working resolution and the keypoint budget; 4 changed what is computed, not the keys).
TEST(DescriptorParameters, DefaultSpecIsTheOneCachesHold) {
  const std::map<std::string, std::string> expected = {
      {"bins", "32"},          {"range", "fixed"},        {"extent_m", "0.35"},   {"filter", "on"},
      {"plane_removal", "on"}, {"max_range_m", "3"},      {"jump_edge_deg", "10"}, {"iss_frame", "6"},
      {"iss_nms", "3"},        {"iss_density", "2"},      {"graph_radius", "3.5"}, {"osada_samples", "20000"},
      {"seed", "7"},           {"working_samples_across", "40"}, {"max_keypoints", "64"},
      {"binning", binningName(DescriptorOptions().histogram.binning)},  {"working_grid", "object"},
      {"working_points", "means"},
      {"budget_taper", descriptorParameter("--budget-taper").get(DescriptorOptions())}};
  EXPECT_EQ(parameterSpec(DescriptorOptions()), expected);
}

// Rows added after specifications were first written (issue 30's grid and binning): a cache or
// model written before them has no such key and reads as it was made — the camera-anchored grid
// and hard binning — while a missing older key is still an error (below).
TEST(DescriptorParameters, SpecsWrittenBeforeARowExistedReadAsTheyWereMade) {
  auto spec = parameterSpec(DescriptorOptions());
  spec.erase("working_grid");
  spec.erase("binning");
  spec.erase("budget_taper");
  spec.erase("working_points");
  const DescriptorOptions old = optionsFromParameterSpec(spec, "model.json");
  EXPECT_EQ(old.working.anchor, VoxelAnchor::CameraGrid);
  EXPECT_EQ(old.histogram.binning, Binning::Hard);
  EXPECT_EQ(old.iss.budget_taper, 0.0);
  EXPECT_EQ(old.working.points, VoxelPoints::Thinned);
  EXPECT_EQ(parameterSpec(old).at("working_grid"), "camera");
}

TEST(DescriptorParameters, EachRowOwnsOneSettingAndRoundTrips) {
  const DescriptorOptions d;
  std::set<std::string> keys, flags;
  for (const auto& p : descriptorParameters()) {
    EXPECT_TRUE(flags.insert(p.flag).second) << p.flag << " twice";
    if (!p.key.empty()) {
      EXPECT_TRUE(keys.insert(p.key).second) << p.key << " twice";
    }
    DescriptorOptions o;
    const std::string v = otherValue(p, d);
    p.set(o, v);
    EXPECT_EQ(p.get(o), v) << p.flag;
    for (const auto& q : descriptorParameters()) {
      if (&q != &p) {
        EXPECT_EQ(q.get(o), q.get(d)) << "setting " << p.flag << " changed " << q.flag;
      }
    }
  }
  // A spec of changed options reads back to the same options.
  DescriptorOptions o;
  row("--bins").set(o, "48");
  row("--no-plane").set(o, "off");
  row("--graph-radius").set(o, "4.5");
  const DescriptorOptions back = optionsFromParameterSpec(parameterSpec(o), "x");
  EXPECT_EQ(back.histogram.bins, 48);
  EXPECT_FALSE(back.filter_options.remove_plane);
  EXPECT_DOUBLE_EQ(back.graph.radius, 4.5);
  EXPECT_EQ(parameterSpec(back), parameterSpec(o));
}

TEST(DescriptorParameters, FieldsTheRowsStandFor) {
  DescriptorOptions o;
  row("--jump-edge-angle").set(o, "0");
  EXPECT_FALSE(o.filter_options.jump_edge);
  row("--jump-edge-angle").set(o, "12.5");
  EXPECT_TRUE(o.filter_options.jump_edge);
  EXPECT_FLOAT_EQ(o.filter_options.jump_edge_angle_deg, 12.5f);
  row("--max-range").set(o, "2.5");
  EXPECT_FLOAT_EQ(o.filter_options.max_range, 2.5f);
  row("--iss-frame").set(o, "7");
  row("--iss-nms").set(o, "5");
  row("--iss-density").set(o, "3");
  EXPECT_DOUBLE_EQ(o.iss.frame_radius, 7);
  EXPECT_DOUBLE_EQ(o.iss.nms_radius, 5);
  EXPECT_DOUBLE_EQ(o.iss.density_radius, 3);
  row("--range").set(o, "per-view");
  EXPECT_EQ(o.histogram.mode, RangeMode::PerView);
  row("--seed").set(o, "18446744073709551615");
  EXPECT_EQ(o.osada.seed, 18446744073709551615ull);
  row("--low-keypoints").set(o, "4");
  EXPECT_EQ(o.low_keypoints, 4);
  EXPECT_EQ(parameterSpec(o).count("low_keypoints"), 0u) << "the warning threshold does not change the features";
}

TEST(DescriptorParameters, BadValuesNameTheReason) {
  DescriptorOptions o;
  const auto reason = [&](const std::string& flag, const std::string& v) {
    try {
      row(flag).set(o, v);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(reason("--bins", "1"), "must be within 2..4096, not '1'");
  EXPECT_EQ(reason("--bins", "3x"), "is not a whole number: '3x'");
  EXPECT_EQ(reason("--iss-nms", "0"), "must be positive, not '0'");
  EXPECT_EQ(reason("--iss-nms", "four"), "is not a number: 'four'");
  EXPECT_EQ(reason("--extent", "-1"), "must be positive, not '-1'");
  EXPECT_EQ(reason("--range", "log"), "must be fixed or per-view, not 'log'");
  EXPECT_EQ(reason("--voxel-grid", "world"), "must be object or camera, not 'world'");
  EXPECT_EQ(reason("--binning", "soft"), "must be hard or linear, not 'soft'");
  EXPECT_EQ(reason("--no-filter", "maybe"), "must be on or off, not 'maybe'");
  EXPECT_EQ(reason("--seed", "-1"), "is not a whole number: '-1'");
  EXPECT_EQ(reason("--jump-edge-angle", "-5"), "must be 0 (off) or positive, not '-5'");
  EXPECT_EQ(o.histogram.bins, 32) << "a refused value leaves the field alone";

  auto spec = parameterSpec(DescriptorOptions());
  spec.erase("iss_nms");
  try {
    optionsFromParameterSpec(spec, "model.json");
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "model.json: feature spec has no 'iss_nms'");
  }
}
