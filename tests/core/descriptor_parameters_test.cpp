#include "keyturn/core/descriptor_parameters.h"

#include <gtest/gtest.h>

#include <set>

#include "keyturn/core/error.h"

using namespace keyturn;

namespace {


// A value other than the default that the row accepts.
std::string otherValue(const DescriptorParameter& p, const DescriptorOptions& d) {
  switch (p.kind) {
    case DescriptorParameter::Kind::Switch: return p.get(d) == "on" ? "off" : "on";
    case DescriptorParameter::Kind::Choice: {
      const std::string now = p.get(d);
      if (p.name == "range") return now == "fixed" ? "per-view" : "fixed";
      if (p.name == "binning") return now == "hard" ? "linear" : "hard";
      if (p.name == "working_grid") return now == "object" ? "camera" : "object";
      if (p.name == "working_points") return now == "means" ? "thinned" : "means";
      if (p.name == "keypoint_placement") return now == "means" ? "salient" : "means";
      if (p.name == "fill_budget") return now == "off" ? "on" : "off";
      ADD_FAILURE() << "no other value known for " << p.name;
      return now;
    }
    case DescriptorParameter::Kind::Integer: return std::to_string(std::stoll(p.get(d)) + 3);
    case DescriptorParameter::Kind::Number:
      return p.name == "budget_taper" || p.name == "nms_margin" ? "0.25" : p.name == "refine_keypoints" ? "0.5"
             : p.name == "curvature_floor"                                 ? "0.1"
                                                                           : "1.25";
  }
  return "";
}

}  // namespace

// The specification of the default options, as feature caches and models of cache version 4 hold
// it (version 3 added the working resolution and the keypoint budget; 4 changed what is computed, not the keys;
// fill_budget on is the default since 2026-12-07).
// The values are docs/descriptors.md's table of defaults, not the library's own.
TEST(DescriptorParameters, DefaultSpecIsTheOneCachesHold) {
  const std::map<std::string, std::string> expected = {
      {"bins", "32"},          {"range", "fixed"},        {"extent_m", "0.35"},   {"filter", "on"},
      {"plane_removal", "on"}, {"max_range_m", "3"},      {"jump_edge_deg", "10"}, {"iss_frame", "6"},
      {"iss_nms", "3"},        {"iss_density", "2"},      {"graph_radius", "3.5"}, {"osada_samples", "20000"},
      {"seed", "7"},           {"working_samples_across", "40"}, {"max_keypoints", "128"},
      {"binning", "linear"},   {"working_grid", "object"}, {"working_points", "means"},
      {"budget_taper", "0"},   {"pdf_smoothing", "1.5"}, {"fill_budget", "on"}};
  EXPECT_EQ(parameterSpec(DescriptorOptions()), expected);
}

// Keypoint refinement is off by default and written only when on: the default specification (and
// every cache named by it) is the one before the option existed, and a refined one differs.
TEST(DescriptorParameters, AnOptionOffByDefaultIsWrittenOnlyWhenSet) {
  EXPECT_EQ(parameterSpec(DescriptorOptions()).count("refine_keypoints"), 0u);
  EXPECT_EQ(parameterSpec(DescriptorOptions()).count("gkpd1_sources"), 0u);
  EXPECT_EQ(parameterSpec(DescriptorOptions()).count("curvature_floor"), 0u);
  EXPECT_EQ(parameterSpec(DescriptorOptions()).count("nms_margin"), 0u);
  // The filled budget, the default since it was measured: written when on, absent (as in every cache
  // and model made before) when off.
  EXPECT_EQ(parameterSpec(DescriptorOptions()).at("fill_budget"), "on");
  EXPECT_TRUE(optionsFromParameterSpec(parameterSpec(DescriptorOptions()), "model.json").iss.fill_budget);
  DescriptorOptions capped;
  descriptorParameter("fill_budget").set(capped, "off");
  EXPECT_EQ(parameterSpec(capped).count("fill_budget"), 0u);
  EXPECT_FALSE(optionsFromParameterSpec(parameterSpec(capped), "model.json").iss.fill_budget);
  DescriptorOptions blended;
  descriptorParameter("gkpd1_sources").set(blended, "8");
  descriptorParameter("curvature_floor").set(blended, "0.1");
  EXPECT_EQ(parameterSpec(blended).at("gkpd1_sources"), "8");
  EXPECT_EQ(parameterSpec(blended).at("curvature_floor"), "0.1");
  EXPECT_EQ(optionsFromParameterSpec(parameterSpec(blended), "model.json").graph.centroid_sources, 8);
  DescriptorOptions refined;
  descriptorParameter("refine_keypoints").set(refined, "0.5");
  const auto spec = parameterSpec(refined);
  ASSERT_EQ(spec.count("refine_keypoints"), 1u);
  EXPECT_EQ(spec.at("refine_keypoints"), "0.5");
  EXPECT_TRUE(optionsFromParameterSpec(spec, "model.json").refine.enabled);
  EXPECT_FALSE(optionsFromParameterSpec(parameterSpec(DescriptorOptions()), "model.json").refine.enabled);
}

// Rows added after specifications were first written (issue 30's grid, binning and smoothing): a
// cache or model written before them has no such key and reads as it was made — the camera-anchored
// grid, hard binning and unsmoothed PDFs — while a missing older key is still an error (below).
TEST(DescriptorParameters, SpecsWrittenBeforeARowExistedReadAsTheyWereMade) {
  auto spec = parameterSpec(DescriptorOptions());
  spec.erase("working_grid");
  spec.erase("binning");
  spec.erase("budget_taper");
  spec.erase("working_points");
  spec.erase("refine_keypoints");
  spec.erase("pdf_smoothing");
  spec.erase("fill_budget");
  const DescriptorOptions old = optionsFromParameterSpec(spec, "model.json");
  EXPECT_EQ(old.histogram.smoothing, 0.0);  // PDFs as they were made: unsmoothed
  EXPECT_EQ(old.working.anchor, VoxelAnchor::CameraGrid);
  EXPECT_EQ(old.histogram.binning, Binning::Hard);
  EXPECT_EQ(old.iss.budget_taper, 0.0);
  EXPECT_EQ(old.working.points, VoxelPoints::Thinned);
  EXPECT_FALSE(old.refine.enabled);
  EXPECT_FALSE(old.iss.fill_budget);  // K as ISS's maxima, at most the budget
  EXPECT_EQ(parameterSpec(old).at("working_grid"), "camera");
}

TEST(DescriptorParameters, EachRowOwnsOneSettingAndRoundTrips) {
  const DescriptorOptions d;
  std::set<std::string> names;
  for (const auto& p : descriptorParameters()) {
    EXPECT_TRUE(names.insert(p.name).second) << p.name << " twice";
    DescriptorOptions o;
    const std::string v = otherValue(p, d);
    p.set(o, v);
    EXPECT_EQ(p.get(o), v) << p.name;
    for (const auto& q : descriptorParameters()) {
      if (&q != &p) {
        EXPECT_EQ(q.get(o), q.get(d)) << "setting " << p.name << " changed " << q.name;
      }
    }
  }
  // A spec of changed options reads back to the same options.
  DescriptorOptions o;
  descriptorParameter("bins").set(o, "48");
  descriptorParameter("plane_removal").set(o, "off");
  descriptorParameter("graph_radius").set(o, "4.5");
  const DescriptorOptions back = optionsFromParameterSpec(parameterSpec(o), "x");
  EXPECT_EQ(back.histogram.bins, 48);
  EXPECT_FALSE(back.filter_options.remove_plane);
  EXPECT_DOUBLE_EQ(back.graph.radius, 4.5);
  EXPECT_EQ(parameterSpec(back), parameterSpec(o));
}

TEST(DescriptorParameters, FieldsTheRowsStandFor) {
  DescriptorOptions o;
  descriptorParameter("jump_edge_deg").set(o, "0");
  EXPECT_FALSE(o.filter_options.jump_edge);
  descriptorParameter("jump_edge_deg").set(o, "12.5");
  EXPECT_TRUE(o.filter_options.jump_edge);
  EXPECT_FLOAT_EQ(o.filter_options.jump_edge_angle_deg, 12.5f);
  descriptorParameter("max_range_m").set(o, "2.5");
  EXPECT_FLOAT_EQ(o.filter_options.max_range, 2.5f);
  descriptorParameter("iss_frame").set(o, "7");
  descriptorParameter("iss_nms").set(o, "5");
  descriptorParameter("iss_density").set(o, "3");
  EXPECT_DOUBLE_EQ(o.iss.frame_radius, 7);
  EXPECT_DOUBLE_EQ(o.iss.nms_radius, 5);
  EXPECT_DOUBLE_EQ(o.iss.density_radius, 3);
  descriptorParameter("range").set(o, "per-view");
  EXPECT_EQ(o.histogram.mode, RangeMode::PerView);
  descriptorParameter("seed").set(o, "18446744073709551615");
  EXPECT_EQ(o.osada.seed, 18446744073709551615ull);
  descriptorParameter("low_keypoints").set(o, "4");
  EXPECT_EQ(o.low_keypoints, 4);
  EXPECT_EQ(parameterSpec(o).count("low_keypoints"), 0u) << "the warning threshold does not change the features";
}

TEST(DescriptorParameters, BadValuesNameTheReason) {
  DescriptorOptions o;
  const auto reason = [&](const std::string& name, const std::string& v) {
    try {
      descriptorParameter(name).set(o, v);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(reason("bins", "1"), "must be within 2..4096, not '1'");
  EXPECT_EQ(reason("bins", "3x"), "is not a whole number: '3x'");
  EXPECT_EQ(reason("iss_nms", "0"), "must be positive, not '0'");
  EXPECT_EQ(reason("iss_nms", "four"), "is not a number: 'four'");
  EXPECT_EQ(reason("extent_m", "-1"), "must be positive, not '-1'");
  EXPECT_EQ(reason("range", "log"), "must be fixed or per-view, not 'log'");
  EXPECT_EQ(reason("working_grid", "world"), "must be object or camera, not 'world'");
  EXPECT_EQ(reason("binning", "soft"), "must be hard, linear or quadratic, not 'soft'");
  EXPECT_EQ(reason("gkpd1_sources", "0"), "must be within 1..64, not '0'");
  EXPECT_EQ(reason("curvature_floor", "2"), "must be within 0..1 and positive, not '2'");
  EXPECT_EQ(reason("filter", "maybe"), "must be on or off, not 'maybe'");
  EXPECT_EQ(reason("seed", "-1"), "is not a whole number: '-1'");
  EXPECT_EQ(reason("jump_edge_deg", "-5"), "must be 0 (off) or positive, not '-5'");
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
