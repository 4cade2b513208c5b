#pragma once
// A standardised training view's value as a model sidecar keeps it (open-set and pose-fusion
// references): 4 decimals, the distances move by < 1e-4. Rounded as a double, so that JSON writes
// "0.3164" and not the float's "0.3163999915122986" (which made the file 2.6 × larger).
#include <cmath>

namespace keyturn::learning {

inline double referenceValue(float v) { return std::round(static_cast<double>(v) * 1e4) / 1e4; }

}  // namespace keyturn::learning
