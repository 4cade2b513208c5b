#pragma once
// The text form of the parameters that shape a view's feature vector, kept in
// feature caches and model sidecars ("bins" → "32", …): the descriptor's
// parameter table (core/descriptor_parameters.h) plus what the cache itself
// fixes (its version, the keypoint detector, the peers' normal radius). One
// mapping in both directions, so a live recogniser computes exactly the
// features its model was trained on.
#include <map>
#include <string>

#include "keyturn/core/descriptor.h"

namespace keyturn::learning {

constexpr int kFeatureCacheVersion = 5;     // 2: 9 significant digits (exact); 3: support rule, working resolution;
                                             // 4: keypoint blocks of filtered views (3 skipped the filter);
                                             // 5: working-resolution points thinned to at least s apart
constexpr double kNormalRadius = 0.012;     // VFH / OUR-CVFH normals, metres (≈ 4 SR4000 pixels at 0.6 m)

std::map<std::string, std::string> featureSpec(const DescriptorOptions& options);
// The options a specification describes (features left at their default: callers choose them).
// Throws keyturn::Error naming `source` and the key for a missing or bad entry, or a cache
// version other than this build's.
DescriptorOptions descriptorOptionsFromSpec(const std::map<std::string, std::string>& spec, const std::string& source);

}  // namespace keyturn::learning
