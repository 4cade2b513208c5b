#pragma once
// Renders what an SR4000 sees of an object standing on a turntable: an
// organized 176 × 144 cloud with amplitude and confidence, ray cast with Embree.
// The sensor model is deliberately simple here (range noise ∝ 1/amplitude,
// mixed pixels from sampling each pixel at its four corners, an amplitude
// threshold, and in libmesasr-sim phase wrap, saturation and integration time); the camera
// simulator grows it.
#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <vector>

#include "keyturn/core/cloud.h"
#include "keyturn/sim/mesh.h"

namespace keyturn::sim {

// SR4000 optics: 176 × 144 pixels, 43.6° horizontal field of view with square
// pixels, so fx = fy = 88 / tan(21.8°) ≈ 219.9 px and the vertical field is 36.3°.
struct Intrinsics {
  int width = 176;
  int height = 144;
  double fx = 219.9, fy = 219.9, cx = 88.0, cy = 72.0;
};

struct SceneView {
  double distance = 0.0;        // camera to object centre (m); 0 = operator placement
  double elevation_deg = 30.0;  // camera above the turntable plane
  double turntable_deg = 0.0;   // object rotation about the turntable (z) axis
  double roll_deg = 0.0;        // camera turned about its optical axis (mounted off level)
  double object_reflectivity = 0.6;
  double table_reflectivity = 0.35;
  double table_half_size = 0.6;  // square table (m) the turntable stands on
  double noise_at_1m = 0.002;    // range σ (m) for a 50% target head-on at 1 m (→ 4 mm at 2 m, 99%)
  double amplitude_threshold = 0.02;  // relative to that same target; below → no return
  std::uint64_t seed = 1;
  bool noise = true;
};

// Distance at which an operator would place the camera: the object's bounding
// sphere spans about 60% of the vertical field, within 0.45–5 m.
double operatorDistance(const Mesh& mesh, const Intrinsics& k = Intrinsics());

// The camera's pose for a view: camera (optical frame) from turntable (z up,
// origin at the table centre) with the table at 0°. Compose with Rz(angle) for
// the object's frame at another angle.
Eigen::Matrix4d cameraFromTurntable(const Mesh& mesh, const SceneView& view, const Intrinsics& k = Intrinsics());

// What the ray through one pixel's centre meets, with no sensor model: the
// geometry a structured-light camera's simulator (structured_light_view.h) starts from.
struct SurfacePixel {
  float depth = 0.f;          // along the optical axis (m); 0 = the ray meets nothing
  float cos_incidence = 0.f;  // |viewing ray · surface normal|
  float cos_light = 0.f;      // |direction to the light · normal|, 0 where the light does not reach
  bool lit = false;           // the light point sees this surface point (no occluder between)
  bool object = false;        // on the object, else on the table
};

class TofViewRenderer {
 public:
  explicit TofViewRenderer(const Mesh& object, Intrinsics k = Intrinsics());
  ~TofViewRenderer();
  TofViewRenderer(const TofViewRenderer&) = delete;
  TofViewRenderer& operator=(const TofViewRenderer&) = delete;

  Cloud render(const SceneView& view) const;
  // One ray per pixel centre (row-major, width × height) and, for each hit, a
  // second ray to `light_cam`, a point in the camera's optical frame (m) such
  // as a structured-light projector beside the lens: a real occlusion query.
  // Rays that miss a sphere around the turning object meet the table's plane analytically;
  // `every_ray_to_embree` casts them all through Embree instead (the tests' reference).
  std::vector<SurfacePixel> castPixelCentres(const SceneView& view, const Eigen::Vector3f& light_cam,
                                             bool every_ray_to_embree = false) const;
  const Intrinsics& intrinsics() const { return k_; }
  const Mesh& object() const { return object_; }

 private:
  struct Scene;
  void buildScene(const SceneView& view) const;  // for the view's turntable angle and table
  Intrinsics k_;
  Mesh object_;
  std::unique_ptr<Scene> scene_;
};

// The view `keyturn bench` always times first and the benchmarks and tests compare with: the
// built-in mug on the turntable at 30°, default camera and noise.
Cloud builtinBenchmarkView();

}  // namespace keyturn::sim
