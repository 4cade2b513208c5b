#include "keyturn/drivers/tof_camera.h"

#include <cmath>
#include <string>

#include "keyturn/core/error.h"
#include "keyturn/core/string_format.h"

namespace keyturn::drivers {

double modulationMHz(int f) {
  static const double mhz[] = {40, 30, 21, 20, 19, 60, 15, 10, 29, 31, 14.5, 15.5};
  return f >= 0 && f < 12 ? mhz[f] : 0.0;
}

int modulationIndex(double mhz) {
  for (int f = 0; f < 12; ++f)
    if (std::abs(modulationMHz(f) - mhz) < 1e-6) return f;
  std::string shown;
  appendFormat(shown, "%g", mhz);
  throw Error("modulation " + shown +
              " MHz is not an SR4000 frequency (40, 30, 21, 20, 19, 60, 15, 10, 29, 31, 14.5, 15.5)");
}

double nonAmbiguousRange(int f) {
  const double mhz = modulationMHz(f);
  return mhz > 0 ? 299.792458 / (2.0 * mhz) : 0.0;
}

}  // namespace keyturn::drivers

#include <algorithm>
#include <cmath>

#include "keyturn/core/error.h"

namespace keyturn::drivers {

TofFrame medianFrame(const std::vector<TofFrame>& frames) {
  if (frames.empty()) throw Error("median of no frames");
  if (frames.size() == 1) return frames[0];
  TofFrame out = frames.back();  // settings, device, timestamp of the last frame
  const std::size_t n = out.distance.size();
  for (const auto& f : frames)
    if (f.distance.size() != n || f.cloud.points.size() != n || f.amplitude.size() != out.amplitude.size() ||
        f.confidence.size() != out.confidence.size() || f.cloud.amplitude.size() != out.cloud.amplitude.size() ||
        f.cloud.confidence.size() != out.cloud.confidence.size())
      throw Error("frames differ in size");
  std::vector<std::pair<std::uint16_t, std::size_t>> samples;
  for (std::size_t i = 0; i < n; ++i) {
    samples.clear();
    for (std::size_t k = 0; k < frames.size(); ++k)
      if (frames[k].distance[i] != 0) samples.emplace_back(frames[k].distance[i], k);
    if (samples.size() * 2 <= frames.size()) {  // most frames had no return here
      out.distance[i] = 0;
      out.cloud.points[i] = Eigen::Vector3f::Constant(std::nanf(""));
      continue;
    }
    const auto mid = samples.begin() + static_cast<std::ptrdiff_t>((samples.size() - 1) / 2);
    std::nth_element(samples.begin(), mid, samples.end());
    const TofFrame& src = frames[mid->second];
    out.distance[i] = src.distance[i];
    // A frame replayed from a cloud without amplitude has no amplitude image.
    if (!out.amplitude.empty()) out.amplitude[i] = src.amplitude[i];
    if (!out.confidence.empty()) out.confidence[i] = src.confidence[i];
    out.cloud.points[i] = src.cloud.points[i];
    if (!out.cloud.amplitude.empty()) out.cloud.amplitude[i] = src.cloud.amplitude[i];
    if (!out.cloud.confidence.empty()) out.cloud.confidence[i] = src.cloud.confidence[i];
  }
  return out;
}

}  // namespace keyturn::drivers
