#pragma once
// Median, min and max of repeated timings: the one summary keyturn_bench reports. Internal.
#include <algorithm>
#include <vector>

namespace keyturn::bench {

struct Spread {
  double median = 0, min = 0, max = 0;
};

inline Spread spread(std::vector<double> v) {
  Spread s;
  if (v.empty()) return s;
  std::sort(v.begin(), v.end());
  s.min = v.front();
  s.max = v.back();
  const std::size_t m = v.size() / 2;
  s.median = v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
  return s;
}

}  // namespace keyturn::bench
