#pragma once
// A depth image read with the wrong depth scale. keyturn's scale is metres per unit (0.001 for
// millimetres); Open3D, and TUM's and many other datasets' readme files, count units per metre
// (1000, 5000, 10000), so the same number puts every point a million or more times too far and the
// filter's range crop leaves nothing. Caught before the filter, said with the numbers that fix it.
#include <cstddef>
#include <string>

#include "keyturn/core/cloud.h"
#include "keyturn/core/error.h"
#include "keyturn/core/filter.h"

namespace keyturn {

// Not an empty view (recognition's "no object"): the user's scale is wrong. Carries the numbers so
// a front end can say it in its own words (its option's name).
class DepthScaleError : public Error {
 public:
  DepthScaleError(const std::string& what, double scale, double median_m, double suggested_scale,
                  double suggested_median_m, std::size_t in_range, std::size_t valid)
      : Error(what), scale(scale), median_m(median_m), suggested_scale(suggested_scale),
        suggested_median_m(suggested_median_m), in_range(in_range), valid(valid) {}
  double scale, median_m;                   // as given, and the median distance from the camera it gives
  double suggested_scale, suggested_median_m;
  std::size_t in_range, valid;              // valid points within the range crop, of all valid points
  // The suggestion is 1 / scale: units per metre given where metres per unit are counted.
  bool reciprocal() const { return suggested_scale * scale > 0.999 && suggested_scale * scale < 1.001; }
};

// Throws DepthScaleError when a depth image read with `scale` (metres per unit) has (almost) nothing
// in the filter's range crop — fewer than 1 % of its valid points — with its median distance more
// than ten times beyond the range, and another scale puts that median inside it: 1 / scale when it
// does (the units-per-metre mistake), else the power of ten times `scale` nearest to 1 m. Returns
// when the range crop is off, the cloud is empty or no scale fits. `what` starts with "FILE: "
// (nothing when `file` is "").
void checkDepthScale(const std::string& file, const Cloud& cloud, double scale, const FilterOptions& filter);

// "1,000,000 m", "1.0 m", "0.05 m": a distance as the message above writes it.
std::string formatMetres(double metres);

}  // namespace keyturn
