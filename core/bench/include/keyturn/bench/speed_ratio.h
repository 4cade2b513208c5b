#pragma once
// How two timings compare, in words a reader cannot misread.
#include <string>

namespace keyturn::bench {

// "2.3× faster" when ours_ms is the shorter time (theirs / ours), "1.4× slower" when
// it is the longer (ours / theirs), "about as fast" within 5 %; "not comparable" when
// either time is missing (≤ 0 or not finite).
std::string speedComparison(double ours_ms, double theirs_ms);

}  // namespace keyturn::bench
