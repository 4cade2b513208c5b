#include "keyturn/studies/view_perturbation.h"

#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "keyturn/core/error.h"

namespace keyturn {
namespace {

Eigen::Vector3d randomDirection(std::mt19937_64& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::Vector3d d;
  do d = Eigen::Vector3d(n(rng), n(rng), n(rng));
  while (d.norm() < 1e-6);
  return d.normalized();
}

// Applies x ↦ R (x − pivot) + pivot + t to every valid point, in double.
void moveRigidly(Cloud& c, const Eigen::Matrix3d& R, const Eigen::Vector3d& pivot, const Eigen::Vector3d& t) {
  for (auto& p : c.points)
    if (Cloud::isValid(p)) p = (R * (p.cast<double>() - pivot) + pivot + t).cast<float>();
}

// Moves every valid point along its own ray to depth z' = depth(z) (the pixel stays the same).
template <typename Depth>
void alongRays(Cloud& c, Depth&& depth) {
  for (auto& p : c.points) {
    if (!Cloud::isValid(p) || !(p.z() > 0.f)) continue;
    const double z = p.z(), z2 = depth(z);
    p = (p.cast<double>() * (z2 / z)).cast<float>();
  }
}

void removePoint(Cloud& c, std::size_t i) { c.points[i] = Eigen::Vector3f::Constant(std::nanf("")); }

// An unorganized cloud without its NaN points (organized ones keep their layout).
void compact(Cloud& c) {
  if (c.organized()) return;
  Cloud out;
  for (std::size_t i = 0; i < c.size(); ++i) {
    if (!Cloud::isValid(c.points[i])) continue;
    out.points.push_back(c.points[i]);
    if (!c.amplitude.empty()) out.amplitude.push_back(c.amplitude[i]);
    if (!c.confidence.empty()) out.confidence.push_back(c.confidence[i]);
  }
  out.width = static_cast<std::uint32_t>(out.points.size());
  out.height = 1;
  c = std::move(out);
}

}  // namespace

bool Perturbation::rigid() const {
  return kind == PerturbationKind::Translate || kind == PerturbationKind::RotateAboutCentroid ||
         kind == PerturbationKind::RotateAboutCamera;
}

const std::vector<Perturbation>& standardPerturbations() {
  using K = PerturbationKind;
  static const std::vector<Perturbation> set = {
      {"translate-1mm", K::Translate, 0.001},
      {"translate-5mm", K::Translate, 0.005},
      {"rotate-centroid-2deg", K::RotateAboutCentroid, 2.0},
      {"rotate-centroid-10deg", K::RotateAboutCentroid, 10.0},
      {"rotate-camera-2deg", K::RotateAboutCamera, 2.0},
      {"rotate-camera-10deg", K::RotateAboutCamera, 10.0},
      {"drop-10pct", K::DropPoints, 0.10},
      {"shift-mask-1px", K::ShiftMask, 1.0},
      {"jitter-0.1mm", K::Jitter, 0.0001},
      {"sensor-noise", K::SensorNoise, 1.0},
      {"depth-round-1mm", K::DepthRounding, 0.001},
  };
  return set;
}

std::vector<Perturbation> perturbationsNamed(const std::string& name) {
  std::vector<Perturbation> out;
  for (const auto& p : standardPerturbations())
    if (name == "all" || p.name == name || (name == "rigid" && p.rigid())) out.push_back(p);
  if (out.empty()) {
    std::string known;
    for (const auto& p : standardPerturbations()) known += ", " + p.name;
    throw Error("no perturbation '" + name + "' (all, rigid" + known + ")");
  }
  return out;
}

std::optional<Cloud> perturbView(const Cloud& view, const Perturbation& pt, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  Cloud c = view;
  constexpr double kDeg = M_PI / 180.0;
  switch (pt.kind) {
    case PerturbationKind::Translate:
      moveRigidly(c, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero(), pt.magnitude * randomDirection(rng));
      break;
    case PerturbationKind::RotateAboutCentroid:
    case PerturbationKind::RotateAboutCamera: {
      const Eigen::Matrix3d R = Eigen::AngleAxisd(pt.magnitude * kDeg, randomDirection(rng)).toRotationMatrix();
      const Eigen::Vector3d pivot =
          pt.kind == PerturbationKind::RotateAboutCentroid ? Eigen::Vector3d(PointSet::fromCloud(c).centroid().cast<double>())
                                                          : Eigen::Vector3d::Zero();
      moveRigidly(c, R, pivot, Eigen::Vector3d::Zero());
      break;
    }
    case PerturbationKind::DropPoints: {
      std::bernoulli_distribution drop(pt.magnitude);
      for (std::size_t i = 0; i < c.size(); ++i)
        if (Cloud::isValid(c.points[i]) && drop(rng)) removePoint(c, i);
      compact(c);
      break;
    }
    case PerturbationKind::ShiftMask: {
      if (!c.organized()) return std::nullopt;
      static const int du[] = {1, -1, 0, 0}, dv[] = {0, 0, 1, -1};
      const int k = std::uniform_int_distribution<int>(0, 3)(rng);
      const int w = static_cast<int>(c.width), h = static_cast<int>(c.height);
      // A pixel stays valid only where the mask moved by (du, dv) still covers it.
      for (int v = 0; v < h; ++v)
        for (int u = 0; u < w; ++u) {
          const int su = u - du[k], sv = v - dv[k];
          const bool covered = su >= 0 && sv >= 0 && su < w && sv < h &&
                               Cloud::isValid(view.points[static_cast<std::size_t>(sv) * w + su]);
          if (!covered) removePoint(c, static_cast<std::size_t>(v) * w + u);
        }
      break;
    }
    case PerturbationKind::Jitter: {
      std::normal_distribution<float> n(0.f, static_cast<float>(pt.magnitude));
      for (auto& p : c.points)
        if (Cloud::isValid(p)) p += Eigen::Vector3f(n(rng), n(rng), n(rng));
      break;
    }
    case PerturbationKind::SensorNoise: {
      std::normal_distribution<double> n(0.0, 1.0);
      alongRays(c, [&](double z) {
        const double sigma = pt.magnitude * (0.0012 + 0.0019 * (z - 0.4) * (z - 0.4));
        return z + sigma * n(rng);
      });
      break;
    }
    case PerturbationKind::DepthRounding:
      alongRays(c, [&](double z) { return std::max(pt.magnitude, std::round(z / pt.magnitude) * pt.magnitude); });
      break;
  }
  return c;
}

}  // namespace keyturn
