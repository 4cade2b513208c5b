// The command line's descriptor options: every flag's default is the library's.
#include <gtest/gtest.h>

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

}  // namespace

TEST(DescriptorFlags, EveryDefaultIsTheLibrarysDefault) {
  CLI::App cli;
  app::DescriptorFlags flags;
  flags.add(cli);
  const DescriptorOptions library;
  for (const auto& p : descriptorParameters()) {
    const std::string flag = app::descriptorFlag(p);
    const CLI::Option* o = cli.get_option(flag);
    ASSERT_NE(o, nullptr) << flag;
    if (p.kind != DescriptorParameter::Kind::Switch)
      EXPECT_EQ(o->get_default_str(), p.get(library)) << flag << " shows another default";
    else
      EXPECT_EQ(p.get(library), "on") << flag << " turns off a setting that is on by default";
  }
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
                                          "--max-keypoints", "--budget-taper", "--refine-keypoints", "--osada-samples", "--seed",
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
