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

StructuredLightFrame StructuredLightRenderer::render(const SceneView& view) const {
  const Intrinsics& k = renderer_.intrinsics();
  if (!cast_ || !sameGeometry(view, cast_view_)) {
    surfaces_ = renderer_.castPixelCentres(view, Eigen::Vector3f(static_cast<float>(model_.baseline), 0.f, 0.f));
    cast_view_ = view;
    cast_ = true;
  }
  const int w = k.width, h = k.height;
  StructuredLightFrame f;
  f.width = w;
  f.height = h;
  f.depth.assign(static_cast<std::size_t>(w) * h, 0.f);
  f.rgb.assign(static_cast<std::size_t>(w) * h * 3, 0);
  f.ir.assign(static_cast<std::size_t>(w) * h, 0);

  std::mt19937_64 rng(view.seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  const double fb = k.fx * model_.baseline;  // disparity (px) × depth (m)
  const double max_theta = model_.max_incidence_deg * M_PI / 180.0;
  for (int v = 0; v < h; ++v) {
    for (int u = 0; u < w; ++u) {
      const std::size_t i = static_cast<std::size_t>(v) * w + u;
      const SurfacePixel& s = surfaces_[i];
      // Colour: albedo shaded by a light at the camera, so no shadow is visible from it.
      const double shade = s.depth > 0 ? 0.2 + 0.8 * s.cos_incidence : 0.0;
      const double albedo[3] = {s.object ? 0.85 : 0.55, s.object ? 0.55 : 0.55, s.object ? 0.30 : 0.52};
      for (int c = 0; c < 3; ++c) f.rgb[3 * i + c] = s.depth > 0 ? toByte(albedo[c] * shade) : toByte(0.12);
      // IR: the projector's light, 10-bit like the PS1080's IR image; dark in its shadow.
      if (s.lit) {
        const double refl = s.object ? view.object_reflectivity : view.table_reflectivity;
        f.ir[i] = static_cast<std::uint16_t>(std::min(1023.0, 400.0 * refl * s.cos_light / (s.depth * s.depth)));
      }

      // Depth: the pattern seen a lateral jitter away, then axial noise, then disparity steps.
      int su = u, sv = v;
      const double theta0 = std::acos(std::clamp(static_cast<double>(s.cos_incidence), 0.0, 1.0));
      if (view.noise && s.depth > 0) {
        const double t = std::min(theta0, M_PI / 2 - 1e-3);
        const double sigma_l = model_.lateral_px + 0.035 * t / (M_PI / 2 - t);
        su = std::clamp(u + static_cast<int>(std::lround(sigma_l * gauss(rng))), 0, w - 1);
        sv = std::clamp(v + static_cast<int>(std::lround(sigma_l * gauss(rng))), 0, h - 1);
      }
      const SurfacePixel& m = surfaces_[static_cast<std::size_t>(sv) * w + su];
      if (m.depth <= 0 || !m.lit) continue;  // no surface, or the projector's shadow
      const double theta = std::acos(std::clamp(static_cast<double>(m.cos_incidence), 0.0, 1.0));
      if (theta > max_theta) continue;
      double z = m.depth;
      if (view.noise) z += axialSigma(z, theta, model_) * gauss(rng);
      if (z <= 0) continue;
      const double disparity = std::round(fb / z / model_.subpixel) * model_.subpixel;
      if (disparity <= 0) continue;
      z = fb / disparity;
      if (z < model_.min_depth || z > model_.max_depth) continue;
      f.depth[i] = static_cast<float>(z);
    }
  }
  return f;
}

}  // namespace keyturn::sim
