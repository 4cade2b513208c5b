#pragma once
// The medians the project takes of measured values (distances, residuals, spacings, scales): one
// home, so that what a median means — which values count, what an even count gives — is said once.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace keyturn {

// The value at the middle of v once sorted: of an even count the upper of the two middle values, so
// always one of v's own values (a measured residual or spacing, not a blend of two). Non-finite values
// are left out; NaN when none is left. Linear time (nth_element), v taken by value.
namespace detail {
template <typename T>
void keepFinite(std::vector<T>& v) {
  v.erase(std::remove_if(v.begin(), v.end(), [](T x) { return !std::isfinite(x); }), v.end());
}
}  // namespace detail

template <typename T>
T upperMedian(std::vector<T> v) {
  detail::keepFinite(v);
  if (v.empty()) return std::numeric_limits<T>::quiet_NaN();
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

// The textbook median: of an even count the mean of the two middle values. Non-finite values are
// left out; NaN when none is left.
inline double median(std::vector<double> v) {
  detail::keepFinite(v);
  if (v.empty()) return std::nan("");
  const std::size_t m = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(m), v.end());
  const double hi = v[m];
  if (v.size() % 2) return hi;
  return 0.5 * (hi + *std::max_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(m)));
}

}  // namespace keyturn
