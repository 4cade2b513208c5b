#pragma once
// The keypoint functions and shape functions keyturn can describe a view with,
// and the rule that gives every feature the same histogram range in every view.
#include <string>
#include <vector>

#include "keyturn/core/histogram.h"

namespace keyturn {

enum class Feature { KPD2, KPD3, KPA3, GKPD1, GKPD2, GKPCD2, D1, D2, D3, D4, A3 };

const std::vector<Feature>& allFeatures();
std::string featureName(Feature f);                  // "kpd2", …
Feature parseFeature(const std::string& name);       // throws keyturn::Error
// "kpd2,kpa3" or "kpd2+kpa3" (a hybrid is the concatenation of its parts).
std::vector<Feature> parseFeatureList(const std::string& list);
bool isKeypointFeature(Feature f);   // needs keypoints (KPD*, KPA3, GKPD*)
bool isGeodesicFeature(Feature f);   // needs the local complete graph

// How histogram ranges are chosen.
//  Fixed (default): a metric range derived from one object extent E (metres):
//    distances [0, E], geodesics [0, 1.5 E], sqrt areas [0, 0.66 E]
//    (an equilateral triangle of side E), cube-root volumes [0, 0.4 E],
//    angles [0, π]. Views of one object at any pose share bins, and absolute
//    size stays in the signature, which separates same-shape objects of other
//    sizes. Values past the range go to the last bin.
//  PerView: lengths scaled to [0, max of that feature in this view]; scale
//    invariant (Osada's normalisation), loses absolute size.
enum class RangeMode { Fixed, PerView };

struct HistogramOptions {
  int bins = 32;
  RangeMode mode = RangeMode::Fixed;
  double extent = 0.35;  // E in metres
  Binning binning = Binning::Linear;  // issue 30: the PDF moves continuously with its values
  double smoothing = 1.5;  // issue 30: kernel density PDFs, a Gaussian of this sigma in bins (0: none)
};

RangeMode parseRangeMode(const std::string& name);
HistogramRange featureRange(Feature f, const HistogramOptions& options);
bool isAngleFeature(Feature f);

}  // namespace keyturn
