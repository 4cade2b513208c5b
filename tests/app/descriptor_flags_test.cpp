// The command line's descriptor options: every flag's default is the library's.
#include <gtest/gtest.h>

#include <map>
#include <set>

#include "descriptor_options.h"
#include "keyturn/core/descriptor_parameters.h"

using namespace keyturn;

namespace {

DescriptorOptions parse(std::vector<std::string> args, bool with_features = true) {
  CLI::App cli;
  app::DescriptorFlags flags;
  flags.add(cli, with_features);
  std::reverse(args.begin(), args.end());
  cli.parse(args);
  return flags.options;
}

// Each row's default as docs/descriptors.md's table of defaults gives it.
const std::map<std::string, std::string> kDocumentedDefaults = {
    {"bins", "32"},           {"range", "fixed"},       {"binning", "linear"},          {"pdf_smoothing", "1.5"},
    {"extent_m", "0.35"},     {"filter", "on"},         {"plane_removal", "on"},        {"max_range_m", "3"},
    {"jump_edge_deg", "10"},  {"iss_frame", "6"},       {"iss_nms", "3"},               {"iss_density", "2"},
    {"graph_radius", "3.5"},  {"gkpd1_sources", "1"},   {"curvature_floor", "0.0001"},  {"working_samples_across", "40"},
    {"working_grid", "object"}, {"working_points", "means"}, {"max_keypoints", "128"},  {"budget_taper", "0"},
    {"fill_budget", "on"},    {"nms_margin", "0"},      {"refine_keypoints", "0"}, {"keypoint_placement", "means"}, {"osada_samples", "20000"}, {"seed", "7"},
    {"low_keypoints", "10"}};

}  // namespace

TEST(DescriptorFlags, EveryDefaultIsTheLibrarysDefault) {
  CLI::App cli;
  app::DescriptorFlags flags;
  flags.add(cli);
  const DescriptorOptions library;
  std::set<std::string> rows;
  for (const auto& p : descriptorParameters()) {
    rows.insert(p.name);
    const std::string flag = app::descriptorFlag(p);
    const CLI::Option* o = cli.get_option(flag);
    ASSERT_NE(o, nullptr) << flag;
    const auto documented = kDocumentedDefaults.find(p.name);
    ASSERT_NE(documented, kDocumentedDefaults.end()) << p.name << " is not in docs/descriptors.md's table of defaults";
    EXPECT_EQ(p.get(library), documented->second) << p.name << ": the library's default is not the documented one";
    if (p.kind != DescriptorParameter::Kind::Switch)
      EXPECT_EQ(o->get_default_str(), documented->second) << flag << " shows another default";
    else
      EXPECT_EQ(documented->second, "on") << flag << " turns off a setting that is on by default";
  }
  for (const auto& [name, value] : kDocumentedDefaults) EXPECT_EQ(rows.count(name), 1u) << name << " is no row";
  EXPECT_EQ(cli.get_option("--features")->get_default_str(), "kpd2,kpd3,kpa3,gkpd1,gkpd2,gkpcd2");
  // Parsing nothing leaves the library's options, field for field.
  const DescriptorOptions none = parse({});
  for (const auto& p : descriptorParameters()) EXPECT_EQ(p.get(none), p.get(library)) << p.name;
  EXPECT_EQ(none.features, library.features);
}

// The flags are the CLI's spelling of the rows' names: the words of the name, or an exception.
// Each exception names a row (a renamed row would leave a stale one), every flag is distinct,
// and the flags are the ones scripts and docs have always used.
TEST(DescriptorFlags, EachRowHasOneFlagMadeFromItsName) {
  std::set<std::string> names, flags;
  for (const auto& p : descriptorParameters()) {
    names.insert(p.name);
    EXPECT_TRUE(flags.insert(app::descriptorFlag(p)).second) << app::descriptorFlag(p) << " twice";
  }
  for (const auto& [name, flag] : app::descriptorFlagExceptions()) EXPECT_EQ(names.count(name), 1u) << name << " is no row";
  EXPECT_EQ(flags, (std::set<std::string>{"--bins", "--range", "--binning", "--pdf-smoothing", "--extent", "--no-filter", "--no-plane",
                                          "--max-range", "--jump-edge-angle", "--iss-frame", "--iss-nms", "--iss-density",
                                          "--graph-radius", "--gkpd1-sources", "--curvature-floor", "--samples-across", "--voxel-grid", "--voxel-points",
                                          "--max-keypoints", "--budget-taper", "--fill-budget", "--nms-margin", "--refine-keypoints", "--keypoint-placement", "--osada-samples", "--seed",
                                          "--low-keypoints"}));
}

TEST(DescriptorFlags, FlagsSetTheirFields) {
  const DescriptorOptions o = parse({"--bins", "48", "--no-plane", "--iss-frame", "7.5", "--features", "kpd2+d2",
                                     "--jump-edge-angle", "0", "--low-keypoints", "4"});
  EXPECT_EQ(o.histogram.bins, 48);
  EXPECT_FALSE(o.filter_options.remove_plane);
  EXPECT_TRUE(o.filter);
  EXPECT_DOUBLE_EQ(o.iss.frame_radius, 7.5);
  EXPECT_EQ(o.features, (std::vector<Feature>{Feature::KPD2, Feature::D2}));
  EXPECT_FALSE(o.filter_options.jump_edge);
  EXPECT_EQ(o.low_keypoints, 4);
  EXPECT_THROW(parse({"--features", "kpd2"}, false), CLI::ParseError) << "the dataset tools take no --features";
}

TEST(DescriptorFlags, ABadValueIsAParseErrorNamingTheFlag) {
  try {
    parse({"--bins", "1"});
    FAIL();
  } catch (const CLI::ValidationError& e) {
    EXPECT_NE(std::string(e.what()).find("--bins"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("must be within 2..4096"), std::string::npos) << e.what();
  }
  EXPECT_THROW(parse({"--iss-nms", "0"}), CLI::ValidationError);
  EXPECT_THROW(parse({"--features", "kpd9"}), CLI::ValidationError);
}
