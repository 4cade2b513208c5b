#include "descriptor_options.h"

#include "keyturn/core/descriptor_parameters.h"
#include "keyturn/core/error.h"

namespace keyturn::app {
namespace {

// A row's own check, reported by CLI11 as "--flag: reason".
CLI::Validator checkWith(const DescriptorParameter& p) {
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
      "", p.flag);
}

std::string featureList(const std::vector<Feature>& features) {
  std::string s;
  for (Feature f : features) s += (s.empty() ? "" : ",") + featureName(f);
  return s;
}

}  // namespace

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
    if (p.kind == DescriptorParameter::Kind::Switch) {
      cmd.add_flag_callback(p.flag, [this, &p] { p.set(options, "off"); }, p.help);
      continue;
    }
    cmd.add_option_function<std::string>(p.flag, [this, &p](const std::string& v) { p.set(options, v); }, p.help)
        ->default_str(p.get(options))
        ->check(checkWith(p));
  }
}

}  // namespace keyturn::app
