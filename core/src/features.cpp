#include "keyturn/core/features.h"

#include <cmath>
#include <sstream>

#include "keyturn/core/error.h"

namespace keyturn {

const std::vector<Feature>& allFeatures() {
  static const std::vector<Feature> all = {Feature::KPD2,  Feature::KPD3,  Feature::KPA3,
                                           Feature::GKPD1, Feature::GKPD2, Feature::GKPCD2,
                                           Feature::D1,    Feature::D2,    Feature::D3,
                                           Feature::D4,    Feature::A3};
  return all;
}

std::string featureName(Feature f) {
  switch (f) {
    case Feature::KPD2: return "kpd2";
    case Feature::KPD3: return "kpd3";
    case Feature::KPA3: return "kpa3";
    case Feature::GKPD1: return "gkpd1";
    case Feature::GKPD2: return "gkpd2";
    case Feature::GKPCD2: return "gkpcd2";
    case Feature::D1: return "d1";
    case Feature::D2: return "d2";
    case Feature::D3: return "d3";
    case Feature::D4: return "d4";
    case Feature::A3: return "a3";
  }
  return "?";
}

Feature parseFeature(const std::string& name) {
  for (Feature f : allFeatures())
    if (featureName(f) == name) return f;
  throw Error("unknown feature '" + name +
              "' (expected kpd2, kpd3, kpa3, gkpd1, gkpd2, gkpcd2, d1, d2, d3, d4, a3)");
}

std::vector<Feature> parseFeatureList(const std::string& list) {
  std::vector<Feature> out;
  std::string token;
  std::stringstream ss(list);
  while (std::getline(ss, token, ',')) {
    std::stringstream parts(token);
    std::string part;
    while (std::getline(parts, part, '+')) {
      if (part.empty()) continue;
      const Feature f = parseFeature(part);
      bool seen = false;
      for (Feature g : out) seen = seen || g == f;
      if (!seen) out.push_back(f);
    }
  }
  if (out.empty()) throw Error("no features given");
  return out;
}

bool isKeypointFeature(Feature f) {
  return f == Feature::KPD2 || f == Feature::KPD3 || f == Feature::KPA3 || isGeodesicFeature(f);
}

bool isGeodesicFeature(Feature f) {
  return f == Feature::GKPD1 || f == Feature::GKPD2 || f == Feature::GKPCD2;
}

bool isAngleFeature(Feature f) { return f == Feature::KPA3 || f == Feature::A3; }

RangeMode parseRangeMode(const std::string& name) {
  if (name == "fixed") return RangeMode::Fixed;
  if (name == "per-view") return RangeMode::PerView;
  throw Error("unknown range mode '" + name + "' (expected fixed or per-view)");
}

HistogramRange featureRange(Feature f, const HistogramOptions& o) {
  const double e = o.extent;
  switch (f) {
    case Feature::KPA3:
    case Feature::A3: return {0.0, M_PI};
    case Feature::KPD2:
    case Feature::D1:
    case Feature::D2: return {0.0, e};
    case Feature::GKPD1:
    case Feature::GKPD2:
    case Feature::GKPCD2: return {0.0, 1.5 * e};
    case Feature::KPD3:
    case Feature::D3: return {0.0, 0.66 * e};
    case Feature::D4: return {0.0, 0.4 * e};
  }
  return {0.0, e};
}

}  // namespace keyturn
