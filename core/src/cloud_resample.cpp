#include "keyturn/core/cloud_resample.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include "keyturn/core/error.h"

namespace keyturn {

namespace {
void copyPoint(const Cloud& from, std::size_t i, Cloud& to) {
  to.points.push_back(from.points[i]);
  if (!from.amplitude.empty()) to.amplitude.push_back(from.amplitude[i]);
  if (!from.confidence.empty()) to.confidence.push_back(from.confidence[i]);
}
}  // namespace

Cloud resampleOrganized(const Cloud& frame, std::size_t pixels) {
  if (!frame.organized()) throw Error("resampling needs an organized frame (this cloud has height 1)");
  if (pixels == 0) throw Error("resampling to 0 pixels");
  const std::size_t W = frame.width, H = frame.height;
  if (pixels >= W * H) return frame;
  const double s = std::sqrt(static_cast<double>(pixels) / static_cast<double>(W * H));
  const std::size_t w = std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(W * s)));
  const std::size_t h = std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(H * s)));
  Cloud out;
  out.width = static_cast<std::uint32_t>(w);
  out.height = static_cast<std::uint32_t>(h);
  out.points.reserve(w * h);
  for (std::size_t v = 0; v < h; ++v) {
    // The source pixel under the centre of output pixel (u, v).
    const std::size_t sv = std::min(H - 1, static_cast<std::size_t>((v + 0.5) * H / h));
    for (std::size_t u = 0; u < w; ++u) {
      const std::size_t su = std::min(W - 1, static_cast<std::size_t>((u + 0.5) * W / w));
      copyPoint(frame, sv * W + su, out);
    }
  }
  return out;
}

Cloud randomSubset(const Cloud& cloud, std::size_t count, unsigned long long seed) {
  std::vector<std::size_t> valid;
  for (std::size_t i = 0; i < cloud.size(); ++i)
    if (Cloud::isValid(cloud.points[i])) valid.push_back(i);
  if (count > valid.size())
    throw Error("cannot draw " + std::to_string(count) + " points from a cloud of " + std::to_string(valid.size()) +
                " valid points");
  // Partial Fisher–Yates: the first `count` entries become a uniform sample.
  std::mt19937_64 rng(seed);
  for (std::size_t i = 0; i < count; ++i) {
    std::uniform_int_distribution<std::size_t> pick(i, valid.size() - 1);
    std::swap(valid[i], valid[pick(rng)]);
  }
  valid.resize(count);
  std::sort(valid.begin(), valid.end());
  Cloud out;
  out.points.reserve(count);
  for (std::size_t i : valid) copyPoint(cloud, i, out);
  out.width = static_cast<std::uint32_t>(count);
  out.height = 1;
  return out;
}

}  // namespace keyturn
