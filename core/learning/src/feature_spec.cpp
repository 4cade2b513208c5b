#include "keyturn/learning/feature_spec.h"

#include <cstdio>

#include "keyturn/core/descriptor_parameters.h"
#include "keyturn/core/error.h"

namespace keyturn::learning {
namespace {

std::string fmt(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", v);
  return b;
}

const std::string& entry(const std::map<std::string, std::string>& spec, const std::string& key,
                         const std::string& source) {
  const auto it = spec.find(key);
  if (it == spec.end()) throw Error(source + ": feature spec has no '" + key + "'");
  return it->second;
}

}  // namespace

std::map<std::string, std::string> featureSpec(const DescriptorOptions& options) {
  std::map<std::string, std::string> spec = parameterSpec(options);
  spec["cache_version"] = std::to_string(kFeatureCacheVersion);
  spec["keypoints"] = "iss";
  spec["normal_radius_m"] = fmt(kNormalRadius);
  return spec;
}

DescriptorOptions descriptorOptionsFromSpec(const std::map<std::string, std::string>& spec, const std::string& source) {
  const std::string& version = entry(spec, "cache_version", source);
  if (version != std::to_string(kFeatureCacheVersion))
    throw Error(source + ": features of cache version " + version + "; this build computes version " +
                std::to_string(kFeatureCacheVersion));
  const std::string& keypoints = entry(spec, "keypoints", source);
  if (keypoints != "iss") throw Error(source + ": keypoints '" + keypoints + "' (only iss is known)");
  return optionsFromParameterSpec(spec, source);
}

}  // namespace keyturn::learning
