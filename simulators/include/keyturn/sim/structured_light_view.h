#pragma once
// What a Kinect-class structured-light depth camera (PrimeSense PS1080: Kinect v1,
// Xtion, and in kind the Orbbec Astra) sees of the simulated rig: the scene ray cast
// noise-free at pixel centres (TofViewRenderer::castPixelCentres), then the
// sensor's measurement model. docs/camera.md gives the model with its sources:
//  - shadow holes: a pixel whose surface point the projector, a baseline beside
//    the lens, cannot see has no pattern to match → 0 (a real occlusion ray);
//  - lateral noise: each pixel reports the depth of a point σ_L ≈ 0.8 px away
//    (Nguyen, Izadi & Lovell 2012), which frays depth edges;
//  - axial noise σ_z = a + b (z − z0)² + c/√z · θ²/(π/2 − θ)² (ibid.);
//  - disparity quantised to 1/8 px, so the depth step f·b/d grows as
//    z² / (f·b) / 8 (Khoshelham & Elberink 2012);
//  - a working range (0.5–4.5 m) and grazing surfaces beyond it return 0.
// Colour is the scene shaded from the depth camera's own viewpoint, so it is
// registered to depth by construction; IR is the scene lit by the projector.
#include <cstdint>
#include <memory>
#include <vector>

#include "keyturn/sim/mesh.h"
#include "keyturn/sim/tof_view.h"

namespace keyturn::sim {

// 640 × 480 with fx = fy = 580 px: 57.8° × 45.0°, a Kinect v1 / Xtion depth camera.
Intrinsics kinectIntrinsics();

struct StructuredLightModel {
  double baseline = 0.075;          // projector beside the camera, along +x (m)
  double subpixel = 1.0 / 8.0;      // disparity step (px)
  double min_depth = 0.5, max_depth = 4.5;  // working range (m)
  double max_incidence_deg = 75.0;  // more grazing: the pattern smears, no match
  double axial_a = 0.0012, axial_b = 0.0019, axial_z0 = 0.4, axial_c = 0.0001;  // σ_z terms (m)
  double lateral_px = 0.8;          // σ_L (px)
  bool noise = true;                // false: only shadows, quantisation and range (deterministic)
};

// One frame; depth in metres (0 = no measurement), colour RGB 8-bit, IR 16-bit.
struct StructuredLightFrame {
  int width = 0, height = 0;
  std::vector<float> depth;
  std::vector<std::uint8_t> rgb;
  std::vector<std::uint16_t> ir;
};

// Where an operator would stand such a camera: tof_view's placement (the object
// spanning ~60% of the field), but no nearer than 0.2 m beyond the minimum range.
double structuredLightOperatorDistance(const Mesh& mesh, const Intrinsics& k, const StructuredLightModel& m);

// Depth step (m) of the disparity quantisation at depth z (m).
double depthStep(double z, double focal_px, const StructuredLightModel& m);
// Axial σ (m) at depth z and incidence angle theta (rad).
double axialSigma(double z, double theta, const StructuredLightModel& m);

class StructuredLightRenderer {
 public:
  explicit StructuredLightRenderer(const Mesh& object, Intrinsics k = kinectIntrinsics(),
                                   StructuredLightModel model = StructuredLightModel());
  ~StructuredLightRenderer();
  StructuredLightRenderer(const StructuredLightRenderer&) = delete;
  StructuredLightRenderer& operator=(const StructuredLightRenderer&) = delete;

  // view.noise and view.seed choose the noise; the geometry is cast again only when
  // the turntable angle changes, so a still scene renders at the camera's rate.
  StructuredLightFrame render(const SceneView& view) const;
  // Casts the view's geometry now (the mesh's BVH, the table's pixels, each pixel's noise model) so
  // that the next render of it only draws noise: a fresh camera's first frame then costs what its
  // later ones do (the simulated OpenNI2 device prepares its scene when it is opened).
  void prepare(const SceneView& view) const;
  // Geometry casts so far, whole or incremental (prepare and render count alike).
  std::size_t casts() const { return casts_; }
  const Intrinsics& intrinsics() const { return renderer_.intrinsics(); }
  const StructuredLightModel& model() const { return model_; }
  // structuredLightOperatorDistance of this renderer's object, camera and model.
  double operatorDistance() const {
    return structuredLightOperatorDistance(renderer_.object(), renderer_.intrinsics(), model_);
  }

 private:
  TofViewRenderer renderer_;
  StructuredLightModel model_;
  // The last cast, for cast_view_, and what follows from it alone: each pixel's
  // incidence angle (rad), lateral σ (px) and axial σ (m), and the colour and IR images.
  void cast(const SceneView& view) const;
  mutable std::vector<SurfacePixel> surfaces_;
  mutable std::vector<float> theta_, lateral_, axial_;  // axial: σ_z (m) at the pixel's depth and angle
  mutable std::vector<std::uint8_t> rgb_;
  mutable std::vector<std::uint16_t> ir_;
  mutable SceneView cast_view_;
  mutable bool cast_ = false;
  mutable std::size_t casts_ = 0;
};

}  // namespace keyturn::sim
