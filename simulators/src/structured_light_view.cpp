#include "keyturn/sim/structured_light_view.h"

#include <algorithm>
#include <cmath>
#include <random>

namespace keyturn::sim {

Intrinsics kinectIntrinsics() {
  Intrinsics k;
  k.width = 640;
  k.height = 480;
  k.fx = k.fy = 580.0;
  k.cx = 320.0;
  k.cy = 240.0;
  return k;
}

double structuredLightOperatorDistance(const Mesh& mesh, const Intrinsics& k, const StructuredLightModel& m) {
  return std::max(operatorDistance(mesh, k), m.min_depth + 0.2);
}

double depthStep(double z, double focal_px, const StructuredLightModel& m) {
  return z * z / (focal_px * m.baseline) * m.subpixel;
}

double axialSigma(double z, double theta, const StructuredLightModel& m) {
  const double t = std::min(theta, M_PI / 2 - 1e-3);
  const double grazing = t * t / ((M_PI / 2 - t) * (M_PI / 2 - t));
  return m.axial_a + m.axial_b * (z - m.axial_z0) * (z - m.axial_z0) + m.axial_c / std::sqrt(z) * grazing;
}

StructuredLightRenderer::StructuredLightRenderer(const Mesh& object, Intrinsics k, StructuredLightModel model)
    : renderer_(object, k), model_(model) {}

StructuredLightRenderer::~StructuredLightRenderer() = default;

namespace {
bool sameGeometry(const SceneView& a, const SceneView& b) {
  return a.turntable_deg == b.turntable_deg && a.distance == b.distance && a.elevation_deg == b.elevation_deg &&
         a.roll_deg == b.roll_deg && a.table_half_size == b.table_half_size;
}

std::uint8_t toByte(double x) { return static_cast<std::uint8_t>(std::clamp(std::lround(x * 255.0), 0L, 255L)); }
}  // namespace

namespace {
bool samePixel(const SurfacePixel& a, const SurfacePixel& b) {
  return a.depth == b.depth && a.cos_incidence == b.cos_incidence && a.cos_light == b.cos_light && a.lit == b.lit &&
         a.object == b.object;
}
}  // namespace

void StructuredLightRenderer::cast(const SceneView& view) const {
  const Intrinsics& k = renderer_.intrinsics();
  std::vector<SurfacePixel> next =
      renderer_.castPixelCentres(view, Eigen::Vector3f(static_cast<float>(model_.baseline), 0.f, 0.f));
  const std::size_t n = static_cast<std::size_t>(k.width) * k.height;
  // While the table turns only the pixels near the object change: the others keep what follows
  // from them (an acos and the noise model's σ a pixel are most of a cast's cost otherwise).
  const bool incremental = cast_ && surfaces_.size() == n && view.object_reflectivity == cast_view_.object_reflectivity &&
                           view.table_reflectivity == cast_view_.table_reflectivity;
  if (!incremental) {
    theta_.assign(n, 0.f);
    lateral_.assign(n, 0.f);
    axial_.assign(n, 0.f);
    rgb_.assign(3 * n, 0);
    ir_.assign(n, 0);
  }
  for (std::size_t i = 0; i < n; ++i) {
    const SurfacePixel& s = next[i];
    if (incremental && samePixel(s, surfaces_[i])) continue;
    const double t = std::min(std::acos(std::clamp(static_cast<double>(s.cos_incidence), 0.0, 1.0)), M_PI / 2 - 1e-3);
    theta_[i] = static_cast<float>(t);
    lateral_[i] = static_cast<float>(model_.lateral_px + 0.035 * t / (M_PI / 2 - t));  // Nguyen et al. σ_L (px)
    axial_[i] = s.depth > 0 ? static_cast<float>(axialSigma(s.depth, t, model_)) : 0.f;
    // Colour: albedo shaded by a light at the camera, so no shadow is visible from it.
    const double shade = 0.2 + 0.8 * s.cos_incidence;
    const double albedo[3] = {s.object ? 0.85 : 0.55, 0.55, s.object ? 0.30 : 0.52};
    for (int c = 0; c < 3; ++c) rgb_[3 * i + c] = s.depth > 0 ? toByte(albedo[c] * shade) : toByte(0.12);
    // IR: the projector's light, 10-bit like the PS1080's IR image; dark in its shadow.
    ir_[i] = 0;
    if (s.lit) {
      const double refl = s.object ? view.object_reflectivity : view.table_reflectivity;
      ir_[i] = static_cast<std::uint16_t>(std::min(1023.0, 400.0 * refl * s.cos_light / (s.depth * s.depth)));
    }
  }
  surfaces_ = std::move(next);
  cast_view_ = view;
  cast_ = true;
  ++casts_;
}

namespace {
// Standard normal samples for the per-pixel noise: 3 per pixel at 30 frames/s are
// too many to draw one by one, so a fixed table of 2^16 is indexed by a fast
// generator (splitmix64) seeded per frame.
const std::vector<float>& normalTable() {
  static const std::vector<float> table = [] {
    std::mt19937_64 rng(20121113);
    std::normal_distribution<float> g(0.f, 1.f);
    std::vector<float> t(1 << 16);
    for (float& x : t) x = g(rng);
    return t;
  }();
  return table;
}

// std::lround's rounding (half away from zero) without its library call: two of them a pixel.
inline int roundToInt(float x) { return static_cast<int>(x >= 0.f ? x + 0.5f : x - 0.5f); }

struct FastNormal {
  std::uint64_t state;
  const std::vector<float>& table = normalTable();
  float operator()() {
    std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return table[(z ^ (z >> 31)) >> 48];
  }
};
}  // namespace

void StructuredLightRenderer::prepare(const SceneView& view) const {
  (void)normalTable();  // the noise table, built once per process
  if (!cast_ || !sameGeometry(view, cast_view_)) cast(view);
}

StructuredLightFrame StructuredLightRenderer::render(const SceneView& view) const {
  const Intrinsics& k = renderer_.intrinsics();
  prepare(view);
  const int w = k.width, h = k.height;
  StructuredLightFrame f;
  f.width = w;
  f.height = h;
  f.depth.assign(static_cast<std::size_t>(w) * h, 0.f);
  f.rgb = rgb_;
  f.ir = ir_;

  FastNormal gauss{view.seed};
  const double fb = k.fx * model_.baseline;  // disparity (px) × depth (m)
  const double step = model_.subpixel;
  const float max_theta = static_cast<float>(model_.max_incidence_deg * M_PI / 180.0);
  for (int v = 0; v < h; ++v) {
    for (int u = 0; u < w; ++u) {
      const std::size_t i = static_cast<std::size_t>(v) * w + u;
      // Depth: the pattern seen a lateral jitter away, then axial noise, then disparity steps.
      std::size_t j = i;
      if (view.noise && surfaces_[i].depth > 0) {
        const float sl = lateral_[i];
        const int su = std::clamp(u + roundToInt(sl * gauss()), 0, w - 1);
        const int sv = std::clamp(v + roundToInt(sl * gauss()), 0, h - 1);
        j = static_cast<std::size_t>(sv) * w + su;
      }
      const SurfacePixel& m = surfaces_[j];
      if (m.depth <= 0 || !m.lit) continue;  // no surface, or the projector's shadow
      if (theta_[j] > max_theta) continue;   // too grazing for the pattern to be matched
      double z = m.depth;
      if (view.noise) z += axial_[j] * gauss();
      if (z <= 0) continue;
      const double disparity = std::round(fb / z / step) * step;
      if (disparity <= 0) continue;
      z = fb / disparity;
      if (z < model_.min_depth || z > model_.max_depth) continue;
      f.depth[i] = static_cast<float>(z);
    }
  }
  return f;
}

}  // namespace keyturn::sim
