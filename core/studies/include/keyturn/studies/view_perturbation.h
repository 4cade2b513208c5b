#pragma once
// Small, documented changes to a view that should not change its description: rigid motions,
// resampling, jitter, the sensor's own noise and depth rounding (docs/descriptors.md,
// "Stability"). Seeded: the same view, perturbation and seed give the same cloud.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "keyturn/core/cloud.h"

namespace keyturn {

enum class PerturbationKind {
  Translate,           // the whole view moved by `magnitude` metres in a random direction
  RotateAboutCentroid, // turned by `magnitude` degrees about a random axis through its centroid
  RotateAboutCamera,   // turned by `magnitude` degrees about a random axis through the camera (origin)
  DropPoints,          // a random `magnitude` fraction of the valid points removed (NaN when organized)
  ShiftMask,           // organized views: the valid-pixel mask moved by one pixel (the edge row lost)
  Jitter,              // Gaussian noise of σ = `magnitude` metres on every coordinate
  SensorNoise,         // depth noise along each ray, σ(z) = 1.2 mm + 1.9 mm·(z/m − 0.4)² (Nguyen et al. 2012, Kinect)
  DepthRounding,       // depth rounded to `magnitude` metres along each ray (a 16-bit PNG in mm: 0.001)
};

struct Perturbation {
  std::string name;  // "translate-2mm", …
  PerturbationKind kind;
  double magnitude = 0;
  bool rigid() const;  // a rigid motion: the description should not change at all
};

// The standard set, in the order reports list it: translate 1 and 5 mm; rotate 2° and 10° about the
// centroid and about the camera; drop 10 %; shift the mask by a pixel; jitter 0.1 mm; sensor noise;
// depth rounded to 1 mm.
const std::vector<Perturbation>& standardPerturbations();
// One of the standard set by name, or "rigid" / "all" for a group; throws keyturn::Error for others.
std::vector<Perturbation> perturbationsNamed(const std::string& name);

// The perturbed view; nullopt when the perturbation does not apply (a mask shift of an unorganized cloud).
std::optional<Cloud> perturbView(const Cloud& view, const Perturbation& perturbation, std::uint64_t seed);

}  // namespace keyturn
