#pragma once
// Structured fuzz input for the chain: bytes decoded into a cloud made of degenerate pieces
// (duplicates, collinear and coplanar runs, clusters at extreme offsets and scales, NaN/inf
// mixes, raw float bit patterns), organized or not, and descriptor options set through the
// parameter table (so every value is one the CLI, Python and a model sidecar could give).
// Shared by fuzz_chain and fuzz_model.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "keyturn/core/cloud.h"
#include "keyturn/core/descriptor.h"
#include "keyturn/core/descriptor_parameters.h"
#include "keyturn/core/error.h"
#include "keyturn/core/features.h"

namespace keyturn::fuzz {

// Reads bytes in order; past the end every read is 0.
class Bytes {
 public:
  Bytes(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  bool empty() const { return pos_ >= size_; }
  std::uint8_t u8() { return pos_ < size_ ? data_[pos_++] : 0; }
  std::uint16_t u16() { return static_cast<std::uint16_t>(u8() | (u8() << 8)); }
  std::uint32_t u32() { return static_cast<std::uint32_t>(u16() | (static_cast<std::uint32_t>(u16()) << 16)); }
  float rawFloat() {
    const std::uint32_t b = u32();
    float f;
    std::memcpy(&f, &b, sizeof f);
    return f;
  }
  // 10^e for e in [lo, hi], signed by a bit.
  double power(double lo, double hi) {
    const std::uint8_t b = u8();
    const double e = lo + (hi - lo) * (b >> 1) / 127.0;
    return (b & 1 ? -1.0 : 1.0) * std::pow(10.0, e);
  }
  double unit() { return u16() / 65535.0; }  // [0, 1]

 private:
  const std::uint8_t* data_;
  std::size_t size_, pos_ = 0;
};

// Kept small so a run of the whole chain under ASan takes milliseconds.
constexpr std::size_t kMaxPoints = 240;

inline Eigen::Vector3f invalidPoint(std::uint8_t kind) {
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  switch (kind % 5) {
    case 0: return Eigen::Vector3f::Constant(nan);
    case 1: return {0.1f, nan, 0.5f};
    case 2: return {inf, 0.f, 1.f};
    case 3: return {0.f, -inf, 1.f};
    default: return {nan, inf, -inf};
  }
}

// An unorganized cloud of pieces, each a kind byte and its parameters.
inline void addPieces(Bytes& in, std::vector<Eigen::Vector3f>& pts) {
  std::uint32_t rng = 0x9e3779b9u;
  auto rand01 = [&] {
    rng ^= rng << 13;
    rng ^= rng >> 17;
    rng ^= rng << 5;
    return (rng >> 8) / 16777216.0;
  };
  while (!in.empty() && pts.size() < kMaxPoints) {
    const std::uint8_t kind = in.u8();
    const std::size_t room = kMaxPoints - pts.size();
    const std::size_t n = std::min<std::size_t>(room, 1 + in.u8());
    // Centre: near the camera, or far from the origin (up to 1e20 m); scale down to 1e-9 m.
    const bool far = in.u8() & 1;
    const Eigen::Vector3d c = far ? Eigen::Vector3d(in.power(-3, 20), in.power(-3, 20), in.power(-3, 20))
                                  : Eigen::Vector3d(in.unit() - 0.5, in.unit() - 0.5, 0.2 + 3 * in.unit());
    const double s = std::abs(in.power(-9, 3));
    rng = in.u32() | 1u;
    auto at = [&](const Eigen::Vector3d& d) { return (c + s * d).cast<float>(); };
    switch (kind % 8) {
      case 0:  // a random cluster in a cube
        for (std::size_t k = 0; k < n; ++k) pts.push_back(at({rand01() - .5, rand01() - .5, rand01() - .5}));
        break;
      case 1:  // copies of one point
        for (std::size_t k = 0; k < n; ++k) pts.push_back(at({0, 0, 0}));
        break;
      case 2: {  // a collinear run, evenly or randomly spaced
        const Eigen::Vector3d dir = Eigen::Vector3d(in.unit() - .5, in.unit() - .5, in.unit() - .5).normalized();
        const bool even = in.u8() & 1;
        for (std::size_t k = 0; k < n; ++k) pts.push_back(at(dir * (even ? k / double(n) : rand01())));
        break;
      }
      case 3: {  // a coplanar grid (or random points on a plane)
        const std::size_t w = 1 + in.u8() % 32;
        const bool random = in.u8() & 1;
        const Eigen::Vector3d a(1, in.unit() - .5, 0), b(in.unit() - .5, 1, in.unit() - .5);
        for (std::size_t k = 0; k < n; ++k)
          pts.push_back(random ? at(a * rand01() + b * rand01()) : at(a * double(k % w) / w + b * double(k / w) / w));
        break;
      }
      case 4: {  // a sphere (float precision far away)
        for (std::size_t k = 0; k < n; ++k) {
          const double z = 2 * rand01() - 1, t = 2 * M_PI * rand01(), r = std::sqrt(1 - z * z);
          pts.push_back(at({r * std::cos(t), r * std::sin(t), z}));
        }
        break;
      }
      case 5:  // invalid points
        for (std::size_t k = 0; k < n; ++k) pts.push_back(invalidPoint(in.u8()));
        break;
      case 6:  // raw float bit patterns (denormals, huge, NaN payloads)
        for (std::size_t k = 0; k < n && !in.empty(); ++k) pts.push_back({in.rawFloat(), in.rawFloat(), in.rawFloat()});
        break;
      default: {  // two points repeated: the two-point cloud, many times
        const Eigen::Vector3f p = at({0, 0, 0}), q = at({1, 0, 0});
        for (std::size_t k = 0; k < n; ++k) pts.push_back(k % 2 ? q : p);
      }
    }
  }
}

// An organized frame: a pinhole camera's rays times a depth pattern, with holes and a shift.
inline Cloud organizedFrame(Bytes& in) {
  Cloud c;
  c.width = 1 + in.u8() % 24;
  c.height = 2 + in.u8() % 20;
  while (static_cast<std::size_t>(c.width) * c.height > kMaxPoints) c.height = std::max<std::uint32_t>(2, c.height / 2);
  while (static_cast<std::size_t>(c.width) * c.height > kMaxPoints) c.width /= 2;
  const double f = std::abs(in.power(-1, 7));  // focal length in pixels: tiny to near-parallel rays
  const double depth = std::abs(in.power(-4, 4));
  const std::uint8_t pattern = in.u8();
  const double amp = in.power(-6, 1), holes = in.unit() * in.unit();
  const Eigen::Vector3d shift(in.power(-3, 20) * (pattern & 0x80 ? 1 : 0), 0, 0);
  std::uint32_t rng = in.u32() | 1u;
  auto rand01 = [&] {
    rng ^= rng << 13;
    rng ^= rng >> 17;
    rng ^= rng << 5;
    return (rng >> 8) / 16777216.0;
  };
  for (std::uint32_t v = 0; v < c.height; ++v)
    for (std::uint32_t u = 0; u < c.width; ++u) {
      const double x = (u - c.width / 2.0) / f, y = (v - c.height / 2.0) / f;
      double d = depth;
      switch (pattern % 6) {
        case 0: break;                                              // a plane facing the camera
        case 1: d += amp * (u > c.width / 2 ? 1 : 0); break;        // a jump edge
        case 2: d += amp * rand01(); break;                          // noise
        case 3: d -= amp * std::max(0.0, 1 - (x * x + y * y)); break;  // a bump
        case 4: d = depth * (1 + amp * u); break;                    // a slanted plane
        default: d = (u + v) % 2 ? depth : depth + amp;              // a checkerboard of two depths
      }
      Eigen::Vector3f p = (Eigen::Vector3d(x * d, y * d, d) + shift).cast<float>();
      if (rand01() < holes) p = invalidPoint(static_cast<std::uint8_t>(u + v));
      c.points.push_back(p);
    }
  if (pattern & 0x40) {  // amplitude and confidence too
    c.amplitude.assign(c.points.size(), static_cast<float>(in.power(-3, 4)));
    c.confidence.assign(c.points.size(), static_cast<float>(in.unit()));
  }
  return c;
}

// A cloud: organized (flag set) or of pieces.
inline Cloud decodeCloud(Bytes& in, bool organized) {
  if (organized) return organizedFrame(in);
  Cloud c;
  addPieces(in, c.points);
  c.width = static_cast<std::uint32_t>(c.points.size());
  c.height = 1;
  return c;
}

// A value for one parameter row, in the forms its parser reads; out-of-range values are refused
// by the row itself (keyturn::Error), as they are for a user. Costly settings are bounded so a run
// stays short: Osada samples, bins and the radii (× resolution) a neighbourhood table grows with.
inline std::string parameterValue(Bytes& in, const DescriptorParameter& p) {
  const std::uint8_t b = in.u8();
  if (p.name == "osada_samples") return std::to_string(1 + in.u16() % 2000);
  if (p.name == "bins") return std::to_string(b % 5 == 0 ? 4096 : 1 + in.u16() % 300);
  if (p.name == "iss_frame" || p.name == "iss_nms" || p.name == "iss_density" || p.name == "graph_radius")
    return std::to_string(std::abs(in.power(-6, 1.5)));
  if (p.name == "gkpd1_sources") return std::to_string(static_cast<int>(b % 20) - 2);  // each source is a search
  // Every choice row's words; a row refuses the others' (as it would a user's typo).
  static const char* const kChoices[] = {"fixed",  "per-view", "hard",  "linear", "quadratic",
                                         "object", "camera",   "means", "thinned"};
  switch (p.kind) {
    case DescriptorParameter::Kind::Switch: return b & 1 ? "on" : "off";
    case DescriptorParameter::Kind::Choice: return kChoices[b % (sizeof kChoices / sizeof kChoices[0])];
    case DescriptorParameter::Kind::Integer: return std::to_string(static_cast<int>(in.u16()) - 8);
    default: {
      char t[40];
      std::snprintf(t, sizeof t, "%.6g", b & 2 ? 0.0 : in.power(-8, 8));
      return t;
    }
  }
}

inline DescriptorOptions decodeOptions(Bytes& in) {
  DescriptorOptions o;
  for (const auto& p : descriptorParameters()) {
    if (!(in.u8() & 1)) continue;  // keep the default
    try {
      p.set(o, parameterValue(in, p));
    } catch (const Error&) {
    }
  }
  // Features: any non-empty subset.
  const std::uint16_t mask = in.u16();
  std::vector<Feature> fs;
  const Feature all[] = {Feature::KPD2, Feature::KPD3, Feature::KPA3, Feature::GKPD1, Feature::GKPD2, Feature::GKPCD2,
                         Feature::D1,   Feature::D2,   Feature::D3,   Feature::D4,    Feature::A3};
  for (std::size_t k = 0; k < sizeof all / sizeof all[0]; ++k)
    if (mask & (1u << k)) fs.push_back(all[k]);
  if (!fs.empty()) o.features = fs;
  o.osada.samples = std::min(o.osada.samples, 2000);  // the default 20,000 would dominate a run
  o.random_keypoints_twin = mask & 0x800;
  o.scaled_twin = mask & 0x1000;
  return o;
}

}  // namespace keyturn::fuzz
