#include <gtest/gtest.h>

#include "keyturn/core/error.h"
#include "keyturn/learning/feature_cache.h"
#include "keyturn/learning/feature_spec.h"
#include "keyturn/learning/recognizer.h"
#include "keyturn/sim/mesh.h"
#include "keyturn/sim/tof_view.h"
#include "support/error_of.h"

using namespace keyturn;
using namespace keyturn::learning;

namespace {

Model untrainedModel(const std::vector<std::string>& blocks, int bins = 32) {
  Model m;
  DescriptorOptions o;
  o.histogram.bins = bins;
  m.info.spec = featureSpec(o);
  m.info.blocks = blocks;
  for (const auto& b : blocks) m.info.inputs += b == "size" ? kSizeBlockWidth : bins;
  m.info.classes = {"mug", "sphere-target"};
  m.classifier = makeClassifier(m.info.params);
  return m;
}

Cloud render(const sim::TofViewRenderer& r, double angle, std::uint64_t seed) {
  sim::SceneView v;
  v.turntable_deg = angle;
  v.seed = seed;
  return r.render(v);
}

}  // namespace

TEST(Recognizer, NamesTheObjectOfUnseenViewsWithTheModelsOwnFeatures) {
  const sim::TofViewRenderer mug(sim::loadMeshOrBuiltin("builtin:mug"));
  const sim::TofViewRenderer sphere(sim::loadMeshOrBuiltin("builtin:sphere-target"));
  const Recognizer describer(untrainedModel({"kpd2", "kpa3"}));
  Matrix x(24, 64);
  std::vector<int> y;
  for (int i = 0; i < 12; ++i) {
    for (int c = 0; c < 2; ++c) {
      const Recognition d = describer.describe(render(c ? sphere : mug, 30.0 * i, 1 + i));
      ASSERT_EQ(d.features.size(), 64u);
      for (int k = 0; k < 64; ++k) x(2 * i + c, k) = d.features[static_cast<std::size_t>(k)];
      y.push_back(c);
    }
  }
  Model trained = untrainedModel({"kpd2", "kpa3"});
  trained.classifier->fit(x, y, 2);
  trained.info.class_means = classMeans(x, y, 2);
  const Recognizer recognizer(std::move(trained));
  // A statistical bar (issue 51): 11 of 12 right. It was a sample of 12 views (every 60°); the filled
  // budget's default named 10 of those, yet more of 144 views every 5° (138 against the capped
  // budget's 134: the sphere 66 and 62 of 72, the mug all). The views are now 48, every 15° between the
  // training angles, the bar the same share (44): measured 47 filled, 46 capped.
  int right = 0;
  for (int i = 0; i < 24; ++i) {
    for (int c = 0; c < 2; ++c) {
      const Recognition r = recognizer.recognize(render(c ? sphere : mug, 7.5 + 15.0 * i, 100 + i));
      ASSERT_EQ(r.probabilities.size(), 2u);
      EXPECT_NEAR(r.probabilities[0] + r.probabilities[1], 1.0f, 1e-4f);
      EXPECT_GT(r.descriptor.keypointCount(), 5);
      EXPECT_EQ(r.descriptor.keypoint_index.size(), r.descriptor.keypoints.size());
      EXPECT_GT(r.filtered.size(), 300u);  // the filtered object, table removed
      right += r.best == c;
    }
  }
  EXPECT_GE(right, 44) << "of 48 unseen views";
}

// A model on scale-normalised twins and the size block sees live what evaluate and train saw in
// the feature cache for the same view: the same values, block by block, in the model's order.
TEST(Recognizer, ScaledTwinsAndSizeLiveAreTheCachesValues) {
  const sim::TofViewRenderer mug(sim::loadMeshOrBuiltin("builtin:mug"));
  const Cloud view = render(mug, 40.0, 3);
  const std::vector<std::string> blocks = {"s_kpd2", "kpa3", "size", "kpd2"};
  const Recognizer live(untrainedModel(blocks));
  EXPECT_EQ(live.blockNames(), blocks);
  const Recognition r = live.describe(view);
  ASSERT_EQ(r.features.size(), 3u * 32u + 4u);
  ASSERT_EQ(r.blocks.size(), 4u);
  EXPECT_EQ(r.blocks[2].size(), 4u);
  EXPECT_NE(r.blocks[0], r.blocks[3]) << "the twin is on other ranges than kpd2";
  const FeatureTable layout = featureLayout(blocks, DescriptorOptions());
  const FeatureRow row = describeCloud(view, DescriptorOptions(), layout);
  ASSERT_EQ(row.values.size(), r.features.size());
  for (std::size_t k = 0; k < r.features.size(); ++k) EXPECT_FLOAT_EQ(row.values[k], r.features[k]) << k;
  EXPECT_NE(keyturn::test::errorOf([] { Recognizer(untrainedModel({"s_kpa3"}), "m4"); }).find("m4: block 's_kpa3' is not computed live"),
            std::string::npos);
}

TEST(Recognizer, RefusesModelsItCannotFeedLive) {
  try {
    Recognizer r(untrainedModel({"kpd2", "esf"}), "m1");
    FAIL() << "esf accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("m1: block 'esf' is not computed live"), std::string::npos) << e.what();
  }
  Model wrong = untrainedModel({"kpd2"});
  wrong.info.inputs = 40;
  EXPECT_THROW(Recognizer(std::move(wrong), "m2"), Error);
  Model old = untrainedModel({"kpd2"});
  old.info.spec["cache_version"] = "1";
  EXPECT_THROW(Recognizer(std::move(old), "m3"), Error);
}

TEST(Recognizer, ABadCloudIsAnErrorNotACrash) {
  const Recognizer r(untrainedModel({"kpd2"}));
  Cloud empty;
  EXPECT_THROW(r.recognize(empty), Error);
  Cloud nan;
  nan.width = 4;
  nan.height = 1;
  nan.points.assign(4, Eigen::Vector3f::Constant(std::nanf("")));
  EXPECT_THROW(r.recognize(nan), Error);
  // A live frame of one point seen 1,000 times (issue 35: SIGSEGV in RadiusSearch::radius, which
  // took the studio down): one line for the studio to show, and the next frame is tried.
  Cloud same;
  same.width = 40;
  same.height = 25;
  same.points.assign(1000, Eigen::Vector3f(0.05f, -0.02f, 0.8f));
  const std::string msg = keyturn::test::errorOf([&] { r.recognize(same); });
  EXPECT_NE(msg.find("degenerate cloud: its"), std::string::npos) << msg;
}

TEST(FeatureSpec, RoundTripsAndNamesTheBadKey) {
  DescriptorOptions p;
  p.histogram.bins = 48;
  p.histogram.extent = 0.4;
  p.filter_options.remove_plane = false;
  p.graph.radius = 4.5;
  const DescriptorOptions q = descriptorOptionsFromSpec(featureSpec(p), "x");
  EXPECT_EQ(featureSpec(q), featureSpec(p));
  EXPECT_EQ(q.histogram.bins, 48);
  EXPECT_FALSE(q.filter_options.remove_plane);
  auto spec = featureSpec(p);
  spec["iss_nms"] = "four";
  try {
    descriptorOptionsFromSpec(spec, "model.json");
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "model.json: feature spec 'iss_nms' is not a number: 'four'");
  }
  spec.erase("iss_nms");
  EXPECT_THROW(descriptorOptionsFromSpec(spec, "model.json"), Error);
  spec = featureSpec(p);
  spec["keypoints"] = "harris";
  EXPECT_THROW(descriptorOptionsFromSpec(spec, "model.json"), Error);
  // The text of the default parameters, as every cache and model of version 4 holds it.
  const std::map<std::string, std::string> expected = {
      {"working_samples_across", "40"}, {"max_keypoints", "128"},
      {"bins", "32"},           {"cache_version", "5"},  {"extent_m", "0.35"},      {"filter", "on"},
      {"graph_radius", "3.5"},  {"iss_density", "2"},    {"iss_frame", "6"},        {"iss_nms", "3"},
      {"jump_edge_deg", "10"},  {"keypoints", "iss"},    {"max_range_m", "3"},      {"normal_radius_m", "0.012"},
      {"osada_samples", "20000"}, {"plane_removal", "on"}, {"range", "fixed"},      {"seed", "7"},
      // issue 30's keys (a spec without them reads as before: camera grid, thinned, hard bins, no taper,
      // unsmoothed PDFs)
      {"working_grid", "object"}, {"working_points", "means"}, {"binning", "linear"}, {"budget_taper", "0"},
      {"pdf_smoothing", "1.5"},
      // issue 49's (absent: K is ISS's maxima, at most the budget)
      {"fill_budget", "on"}};
  EXPECT_EQ(featureSpec(DescriptorOptions()), expected);
}

TEST(FeatureSpec, IntegersAreParsedAsIntegersNotCastFromDoubles) {
  DescriptorOptions p;
  p.osada.seed = 18446744073709551557ull;  // past 2^53: a double would lose its last digits
  EXPECT_EQ(descriptorOptionsFromSpec(featureSpec(p), "x").osada.seed, p.osada.seed);
  auto err = [&](const std::string& key, const std::string& value) {
    auto spec = featureSpec(DescriptorOptions{});
    spec[key] = value;
    return keyturn::test::errorOf([&] { descriptorOptionsFromSpec(spec, "features.csv"); });
  };
  EXPECT_EQ(err("bins", "1e30"), "features.csv: feature spec 'bins' is not a whole number: '1e30'");
  EXPECT_EQ(err("bins", "4097"), "features.csv: feature spec 'bins' must be within 2..4096, not '4097'");
  EXPECT_EQ(err("osada_samples", "2.5"), "features.csv: feature spec 'osada_samples' is not a whole number: '2.5'");
  EXPECT_EQ(err("seed", "-1"), "features.csv: feature spec 'seed' is not a whole number: '-1'");
  EXPECT_EQ(err("max_keypoints", "-3"), "features.csv: feature spec 'max_keypoints' must be at least 0, not '-3'");
}

TEST(ClassMeans, IgnoreMissingValues) {
  Matrix x(3, 2);
  x << 1, std::nanf(""), 3, 4, 10, 20;
  const auto m = classMeans(x, {0, 0, 1}, 2);
  ASSERT_EQ(m.size(), 2u);
  EXPECT_FLOAT_EQ(m[0][0], 2.f);
  EXPECT_FLOAT_EQ(m[0][1], 4.f);
  EXPECT_FLOAT_EQ(m[1][1], 20.f);
}
