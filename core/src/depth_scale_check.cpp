#include "keyturn/core/depth_scale_check.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "keyturn/core/median.h"
#include "keyturn/core/string_format.h"

namespace keyturn {

std::string formatMetres(double m) {
  std::string out;
  if (m < 1000) {
    appendFormat(out, m < 0.1 ? "%.3g m" : "%.1f m", m);
    return out;
  }
  std::string digits;
  appendFormat(digits, "%.0f", m);
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out + " m";
}

void checkDepthScale(const std::string& file, const Cloud& cloud, double scale, const FilterOptions& f) {
  if (!f.crop_range || !(scale > 0)) return;
  const double lo = f.min_range > 0 ? f.min_range : 0.0;
  const double hi = f.max_range > 0 ? f.max_range : std::numeric_limits<double>::infinity();
  if (lo == 0 && std::isinf(hi)) return;
  std::vector<double> r;
  r.reserve(cloud.points.size());
  std::size_t in_range = 0;
  for (const auto& p : cloud.points)
    if (Cloud::isValid(p)) {
      r.push_back(p.cast<double>().norm());
      if (r.back() >= lo && r.back() <= hi) ++in_range;
    }
  if (r.empty() || in_range * 100 >= r.size()) return;  // 1 % or more in range: the scale is not the problem
  const double median = upperMedian(r);  // a copy: r.size() is reported below
  if (!(median > 10 * hi || median < lo / 10)) return;  // near the range: a scene, not a scale, problem

  const auto fits = [&](double s) { return median / scale * s >= lo && median / scale * s <= hi; };
  double suggested = 1 / scale;
  if (!fits(suggested)) {
    suggested = 0;
    for (int k = -12; k <= 12; ++k) {
      const double s = scale * std::pow(10.0, k);
      if (k != 0 && fits(s) &&
          (suggested == 0 || std::abs(std::log(median / scale * s)) < std::abs(std::log(median / scale * suggested))))
        suggested = s;
    }
    if (suggested == 0) return;
  }
  DepthScaleError e("", scale, median, suggested, median / scale * suggested, in_range, r.size());
  std::string reciprocal;
  if (e.reciprocal()) appendFormat(reciprocal, " (1/%g)", scale);
  std::string what;
  appendFormat(what, "%s%sdepth scale %g (metres per unit) puts the median distance at %s, %zu of %zu points within "
               "the %g–%g m the filter keeps; %g%s would put it at %s",
               file.c_str(), file.empty() ? "" : ": ", scale, formatMetres(median).c_str(), in_range, r.size(), lo, hi, suggested,
               reciprocal.c_str(), formatMetres(e.suggested_median_m).c_str());
  throw DepthScaleError(what, scale, median, suggested, e.suggested_median_m, in_range, r.size());
}

}  // namespace keyturn
