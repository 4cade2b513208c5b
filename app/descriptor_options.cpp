#include "descriptor_options.h"

#include "keyturn/core/error.h"

namespace keyturn::app {
namespace {

// A row's own check, reported by CLI11 as "--flag: reason".
CLI::Validator checkWith(const DescriptorParameter& p, const std::string& flag) {
  return CLI::Validator(
      [&p](std::string& text) {
        DescriptorOptions scratch;
        try {
          p.set(scratch, text);
        } catch (const Error& e) {
          return std::string(e.what());
        }
        return std::string();
      },
      "", flag);
}

std::string featureList(const std::vector<Feature>& features) {
  std::string s;
  for (Feature f : features) s += (s.empty() ? "" : ",") + featureName(f);
  return s;
}

}  // namespace

const std::map<std::string, std::string>& descriptorFlagExceptions() {
  // Shorter words than the specification's (its keys name units and groups), and flags older
  // than the keys they set.
  static const std::map<std::string, std::string> flags = {
      {"extent_m", "--extent"},         {"plane_removal", "--no-plane"},
      {"max_range_m", "--max-range"},   {"jump_edge_deg", "--jump-edge-angle"},
      {"working_samples_across", "--samples-across"}, {"working_grid", "--voxel-grid"},
      {"working_points", "--voxel-points"}};
  return flags;
}

std::string descriptorFlag(const DescriptorParameter& p) {
  const auto it = descriptorFlagExceptions().find(p.name);
  if (it != descriptorFlagExceptions().end()) return it->second;
  std::string flag = p.kind == DescriptorParameter::Kind::Switch ? "--no-" : "--";
  for (char c : p.name) flag += c == '_' ? '-' : c;
  return flag;
}

void DescriptorFlags::add(CLI::App& cmd, bool with_features) {
  if (with_features)
    cmd.add_option_function<std::string>(
           "--features", [this](const std::string& list) { options.features = parseFeatureList(list); },
           "Comma-separated keypoint/shape functions: kpd2,kpd3,kpa3,gkpd1,gkpd2,gkpcd2,d1,d2,d3,d4,a3 ('+' joins a "
           "hybrid, same effect)")
        ->default_str(featureList(options.features))
        ->check(CLI::Validator(
            [](std::string& list) {
              try {
                parseFeatureList(list);
              } catch (const Error& e) {
                return std::string(e.what());
              }
              return std::string();
            },
            "", "features"));
  for (const DescriptorParameter& p : descriptorParameters()) {
    const std::string flag = descriptorFlag(p);
    if (p.kind == DescriptorParameter::Kind::Switch) {
      cmd.add_flag_callback(flag, [this, &p] { p.set(options, "off"); }, p.help);
      continue;
    }
    cmd.add_option_function<std::string>(flag, [this, &p](const std::string& v) { p.set(options, v); }, p.help)
        ->default_str(p.get(options))
        ->check(checkWith(p, flag));
  }
}

}  // namespace keyturn::app
