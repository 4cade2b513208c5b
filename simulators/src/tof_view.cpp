#include "keyturn/sim/tof_view.h"

#include <embree3/rtcore.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "keyturn/core/error.h"

namespace keyturn::sim {

namespace {
constexpr float kPi = static_cast<float>(M_PI);
}

struct TofViewRenderer::Scene {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  unsigned object_id = 0;
  unsigned table_id = 0;
  mutable double built_angle = std::numeric_limits<double>::quiet_NaN();
  mutable double built_table = std::numeric_limits<double>::quiet_NaN();
  // castPixelCentres' pixels that see the bare table and whose light the object cannot block,
  // for one camera placement and light: the same at every turntable angle, so kept between
  // frames. `near_object` lists the others (their rays meet the sphere around the object).
  struct TableCast {
    double distance = std::numeric_limits<double>::quiet_NaN(), elevation = 0, roll = 0, table = 0;
    Eigen::Vector3f light_cam = Eigen::Vector3f::Zero();
    std::vector<SurfacePixel> pixels;
    std::vector<std::uint32_t> near_object;
    bool matches(const SceneView& v, const Eigen::Vector3f& light) const {
      return distance == v.distance && elevation == v.elevation_deg && roll == v.roll_deg &&
             table == v.table_half_size && light_cam == light;
    }
  };
  TableCast table_cast;
  ~Scene() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

double operatorDistance(const Mesh& mesh, const Intrinsics& k) {
  const Eigen::Vector3f size = mesh.boundsMax() - mesh.boundsMin();
  const double radius = 0.5 * size.norm();
  const double half_fov_v = std::atan(0.5 * k.height / k.fy);
  const double d = radius / std::tan(0.6 * half_fov_v);
  return std::clamp(d, 0.45, 5.0);
}

namespace {
struct CameraPlacement {
  Eigen::Vector3f eye;
  Eigen::Matrix3f cam_to_world;  // columns: right, down, forward
};

CameraPlacement placeCamera(const Mesh& mesh, const SceneView& view, const Intrinsics& k) {
  // On the -y side, raised by the elevation, looking at the object centre.
  const Eigen::Vector3f lo = mesh.boundsMin(), hi = mesh.boundsMax();
  const Eigen::Vector3f target(0.f, 0.f, 0.5f * (lo.z() + hi.z()));
  const double dist = view.distance > 0 ? view.distance : operatorDistance(mesh, k);
  const float el = static_cast<float>(view.elevation_deg) * kPi / 180.f;
  CameraPlacement c;
  c.eye = target + static_cast<float>(dist) * Eigen::Vector3f(0.f, -std::cos(el), std::sin(el));
  const Eigen::Vector3f fwd = (target - c.eye).normalized();
  const Eigen::Vector3f level_right = fwd.cross(Eigen::Vector3f::UnitZ()).normalized();
  const Eigen::Vector3f level_down = fwd.cross(level_right);
  const float roll = static_cast<float>(view.roll_deg) * kPi / 180.f;
  const Eigen::Vector3f right = std::cos(roll) * level_right + std::sin(roll) * level_down;
  const Eigen::Vector3f down = fwd.cross(right);
  c.cam_to_world << right, down, fwd;
  return c;
}
}  // namespace

Eigen::Matrix4d cameraFromTurntable(const Mesh& mesh, const SceneView& view, const Intrinsics& k) {
  const CameraPlacement c = placeCamera(mesh, view, k);
  Eigen::Matrix4d world_from_cam = Eigen::Matrix4d::Identity();
  world_from_cam.topLeftCorner<3, 3>() = c.cam_to_world.cast<double>();
  world_from_cam.topRightCorner<3, 1>() = c.eye.cast<double>();
  return world_from_cam.inverse();
}

TofViewRenderer::TofViewRenderer(const Mesh& object, Intrinsics k)
    : k_(k), object_(object), scene_(std::make_unique<Scene>()) {
  if (object_.triangles.empty()) throw Error("simulated scene: object mesh has no triangles");
  scene_->device = rtcNewDevice("threads=1");
  if (!scene_->device) throw Error("simulated scene: Embree device could not be created");
}

TofViewRenderer::~TofViewRenderer() = default;

namespace {

unsigned addTriangles(RTCDevice dev, RTCScene scene, const std::vector<Eigen::Vector3f>& v,
                      const std::vector<Eigen::Vector3i>& t) {
  RTCGeometry g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* vb = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0,
                                                         RTC_FORMAT_FLOAT3, 3 * sizeof(float), v.size()));
  for (std::size_t i = 0; i < v.size(); ++i)
    for (int c = 0; c < 3; ++c) vb[3 * i + c] = v[i][c];
  auto* ib = static_cast<unsigned*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0,
                                                            RTC_FORMAT_UINT3, 3 * sizeof(unsigned), t.size()));
  for (std::size_t i = 0; i < t.size(); ++i)
    for (int c = 0; c < 3; ++c) ib[3 * i + c] = static_cast<unsigned>(t[i][c]);
  rtcCommitGeometry(g);
  const unsigned id = rtcAttachGeometry(scene, g);
  rtcReleaseGeometry(g);
  return id;
}

// The first surface along the ray from `origin` in direction `dir` (geomID invalid when none).
RTCRayHit firstHit(RTCScene scene, RTCIntersectContext& ctx, const Eigen::Vector3f& origin, const Eigen::Vector3f& dir) {
  RTCRayHit rh;
  rh.ray.org_x = origin.x(); rh.ray.org_y = origin.y(); rh.ray.org_z = origin.z();
  rh.ray.dir_x = dir.x(); rh.ray.dir_y = dir.y(); rh.ray.dir_z = dir.z();
  rh.ray.tnear = 0.f;
  rh.ray.tfar = std::numeric_limits<float>::infinity();
  rh.ray.mask = ~0u;
  rh.ray.flags = 0;
  rh.ray.time = 0.f;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene, &ctx, &rh);
  return rh;
}

struct Hit {
  bool valid = false;
  float range = 0.f;
  float amplitude = 0.f;
};

}  // namespace

void TofViewRenderer::buildScene(const SceneView& view) const {
  // (Re)build the scene when the turntable angle changes: the object is turned
  // on the CPU, which for ≤ 10k triangles costs far less than the BVH build.
  if (!(scene_->built_angle == view.turntable_deg) || !(scene_->built_table == view.table_half_size)) {
    if (scene_->scene) rtcReleaseScene(scene_->scene);
    scene_->scene = rtcNewScene(scene_->device);
    const Eigen::Matrix3f rot =
        Eigen::AngleAxisf(static_cast<float>(view.turntable_deg) * kPi / 180.f, Eigen::Vector3f::UnitZ())
            .toRotationMatrix();
    std::vector<Eigen::Vector3f> v(object_.vertices.size());
    for (std::size_t i = 0; i < v.size(); ++i) v[i] = rot * object_.vertices[i];
    scene_->object_id = addTriangles(scene_->device, scene_->scene, v, object_.triangles);
    const float s = static_cast<float>(view.table_half_size);
    scene_->table_id = addTriangles(scene_->device, scene_->scene,
                                    {{-s, -s, 0.f}, {s, -s, 0.f}, {s, s, 0.f}, {-s, s, 0.f}},
                                    {{0, 1, 2}, {0, 2, 3}});
    rtcCommitScene(scene_->scene);
    scene_->built_angle = view.turntable_deg;
    scene_->built_table = view.table_half_size;
  }
}

Cloud TofViewRenderer::render(const SceneView& view) const {
  buildScene(view);
  const CameraPlacement placement = placeCamera(object_, view, k_);
  const Eigen::Vector3f& eye = placement.eye;
  const Eigen::Matrix3f& cam_to_world = placement.cam_to_world;

  std::mt19937_64 rng(view.seed);
  std::normal_distribution<float> gauss(0.f, 1.f);
  // Reference amplitude: a 50% reflective target, head-on, at 1 m.
  const float a_ref = 0.5f;
  constexpr float kConfidenceHalfSigma = 0.004f;  // m
  const float a_min = static_cast<float>(view.amplitude_threshold) * a_ref;

  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  // Rays through the (W+1) × (H+1) pixel corners: each pixel mixes its four
  // corners, so a pixel straddling a depth edge mixes both surfaces (a ToF
  // mixed pixel) at a quarter of the rays of 2 × 2 sub-pixel sampling.
  const int cw = k_.width + 1, ch = k_.height + 1;
  std::vector<Hit> corner(static_cast<std::size_t>(cw) * ch);
  for (int v = 0; v < ch; ++v) {
    for (int u = 0; u < cw; ++u) {
      const Eigen::Vector3f d = (cam_to_world * Eigen::Vector3f(static_cast<float>((u - k_.cx) / k_.fx),
                                                                static_cast<float>((v - k_.cy) / k_.fy), 1.f))
                                    .normalized();
      RTCRayHit rh = firstHit(scene_->scene, ctx, eye, d);
      if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;
      Hit& h = corner[static_cast<std::size_t>(v) * cw + u];
      const Eigen::Vector3f n = Eigen::Vector3f(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z).normalized();
      const float refl = static_cast<float>(rh.hit.geomID == scene_->object_id ? view.object_reflectivity
                                                                               : view.table_reflectivity);
      h.valid = true;
      h.range = rh.ray.tfar;  // d is unit length
      h.amplitude = refl * std::abs(n.dot(d)) / (h.range * h.range);
    }
  }

  Cloud cloud;
  cloud.width = static_cast<std::uint32_t>(k_.width);
  cloud.height = static_cast<std::uint32_t>(k_.height);
  const std::size_t n = static_cast<std::size_t>(k_.width) * k_.height;
  cloud.points.assign(n, Eigen::Vector3f::Constant(std::nanf("")));
  cloud.amplitude.assign(n, 0.f);
  cloud.confidence.assign(n, 0.f);
  for (int v = 0; v < k_.height; ++v) {
    for (int u = 0; u < k_.width; ++u) {
      // Where the corners disagree in range the pixel mixes both surfaces,
      // amplitude-weighted, which is how ToF jump edges arise.
      float asum = 0.f, rsum = 0.f;  // amplitude and amplitude-weighted range
      const std::size_t c0 = static_cast<std::size_t>(v) * cw + u;
      for (const Hit& h : {corner[c0], corner[c0 + 1], corner[c0 + cw], corner[c0 + cw + 1]}) {
        if (!h.valid) continue;
        asum += h.amplitude;
        rsum += h.amplitude * h.range;
      }
      const float amp = asum / 4.f;
      const std::size_t i = static_cast<std::size_t>(v) * k_.width + u;
      cloud.amplitude[i] = amp;
      if (asum <= 0.f || amp < a_min) continue;  // below the amplitude threshold: distance 0
      float range = rsum / asum;
      if (view.noise) range += static_cast<float>(view.noise_at_1m) * (a_ref / amp) * gauss(rng);
      const Eigen::Vector3f ray = Eigen::Vector3f(static_cast<float>((u + 0.5 - k_.cx) / k_.fx),
                                                  static_cast<float>((v + 0.5 - k_.cy) / k_.fy), 1.f)
                                      .normalized();
      cloud.points[i] = range * ray;
      // Graded like the SR4000's confidence map: falls with the pixel's range noise σ (∝ 1/amplitude),
      // 1/2 where σ is the data sheet's 4 mm; independent of the amplitude threshold.
      const float sigma = static_cast<float>(view.noise_at_1m) * (a_ref / amp);
      cloud.confidence[i] = kConfidenceHalfSigma / (kConfidenceHalfSigma + sigma);
    }
  }
  return cloud;
}

namespace {

// A sphere holding the object at every turntable angle (centred on the turntable's axis).
// A ray that misses it can only meet the table, which is the plane z = 0: most of a 640 × 480
// frame, found without Embree; and the same at every turntable angle, so kept (the simulated
// OpenNI2 camera casts every frame anew while the table turns: docs/benchmarks.md,
// BM_RenderStructuredLightTurning).
struct BoundingSphere {
  Eigen::Vector3f centre = Eigen::Vector3f::Zero();
  float radius = 0.f;
  // Whether the segment origin + t·dir (dir unit length), t in [t0, t1], meets the sphere.
  bool meets(const Eigen::Vector3f& origin, const Eigen::Vector3f& dir, float t0, float t1) const {
    const Eigen::Vector3f oc = origin - centre;
    const float b = oc.dot(dir);
    const float c = oc.squaredNorm() - radius * radius;
    const float disc = b * b - c;
    if (disc < 0.f) return false;
    const float root = std::sqrt(disc);
    return -b + root >= t0 && -b - root <= t1;
  }
};

BoundingSphere turningBound(const Mesh& object) {
  float r2 = 0.f, z0 = std::numeric_limits<float>::infinity(), z1 = -z0;
  for (const Eigen::Vector3f& v : object.vertices) {
    r2 = std::max(r2, v.x() * v.x() + v.y() * v.y());
    z0 = std::min(z0, v.z());
    z1 = std::max(z1, v.z());
  }
  BoundingSphere b;
  if (object.vertices.empty()) return b;
  b.centre = Eigen::Vector3f(0.f, 0.f, 0.5f * (z0 + z1));
  // 1 mm more than the vertices reach: a ray grazing the object is always left to Embree.
  b.radius = std::sqrt(r2 + 0.25f * (z1 - z0) * (z1 - z0)) + 1e-3f;
  return b;
}

}  // namespace

std::vector<SurfacePixel> TofViewRenderer::castPixelCentres(const SceneView& view, const Eigen::Vector3f& light_cam,
                                                            bool every_ray_to_embree) const {
  buildScene(view);
  const CameraPlacement placement = placeCamera(object_, view, k_);
  const Eigen::Vector3f light = placement.eye + placement.cam_to_world * light_cam;
  const BoundingSphere bound = turningBound(object_);
  const float table = static_cast<float>(view.table_half_size);
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  // One pixel. `through_embree`: both rays go to Embree; otherwise a ray that misses the sphere
  // is answered by the table's plane. Returns false where the pixel needs Embree after all.
  auto castPixel = [&](std::size_t i, bool through_embree, SurfacePixel& s) {
    const int u = static_cast<int>(i % static_cast<std::size_t>(k_.width)), v = static_cast<int>(i / k_.width);
    const Eigen::Vector3f ray_cam(static_cast<float>((u + 0.5 - k_.cx) / k_.fx),
                                  static_cast<float>((v + 0.5 - k_.cy) / k_.fy), 1.f);
    const Eigen::Vector3f d = (placement.cam_to_world * ray_cam).normalized();
    float t_hit = 0.f;
    Eigen::Vector3f n;
    bool on_object = false;
    if (through_embree) {
      RTCRayHit rh = firstHit(scene_->scene, ctx, placement.eye, d);
      if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return true;
      t_hit = rh.ray.tfar;
      n = Eigen::Vector3f(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z).normalized();
      on_object = rh.hit.geomID == scene_->object_id;
    } else {  // the table's plane, or nothing
      if (bound.meets(placement.eye, d, 0.f, std::numeric_limits<float>::infinity())) return false;
      if (std::abs(d.z()) < 1e-12f) return true;
      t_hit = -placement.eye.z() / d.z();
      if (!(t_hit > 0.f)) return true;
      const Eigen::Vector3f p = placement.eye + t_hit * d;
      if (std::abs(p.x()) > table || std::abs(p.y()) > table) return true;
      n = Eigen::Vector3f::UnitZ();
    }
    const Eigen::Vector3f p = placement.eye + t_hit * d;
    s.depth = t_hit / ray_cam.norm();  // range → z along the optical axis
    s.cos_incidence = std::abs(n.dot(d));
    s.object = on_object;
    // The light sees p unless something lies between them; the segment stops
    // short of p so that p's own triangle does not count.
    const Eigen::Vector3f to_light = light - p;
    const float dist = to_light.norm();
    const Eigen::Vector3f l = to_light / dist;
    // Lit only from the side the camera sees (a surface never lights its back face).
    if (n.dot(l) * n.dot(-d) <= 0.f) return true;
    const float t_near = 1e-4f * std::max(1.f, dist);
    if (!through_embree) {
      if (bound.meets(p, l, t_near, dist)) return false;
      s.lit = true;  // from the table, only the object can stand in the light's way
    } else {
      RTCRay r;
      r.org_x = p.x(); r.org_y = p.y(); r.org_z = p.z();
      r.dir_x = l.x(); r.dir_y = l.y(); r.dir_z = l.z();
      r.tnear = t_near;
      r.tfar = dist;
      r.mask = ~0u;
      r.flags = 0;
      r.time = 0.f;
      rtcOccluded1(scene_->scene, &ctx, &r);
      s.lit = r.tfar >= 0.f;  // Embree sets tfar to -inf when the ray is blocked
    }
    s.cos_light = s.lit ? std::abs(n.dot(l)) : 0.f;
    return true;
  };

  const std::size_t n = static_cast<std::size_t>(k_.width) * k_.height;
  if (every_ray_to_embree) {
    std::vector<SurfacePixel> out(n);
    for (std::size_t i = 0; i < n; ++i) castPixel(i, true, out[i]);
    return out;
  }
  auto& cache = scene_->table_cast;
  if (!cache.matches(view, light_cam)) {
    cache = Scene::TableCast();
    cache.pixels.assign(n, SurfacePixel());
    for (std::size_t i = 0; i < n; ++i)
      if (!castPixel(i, false, cache.pixels[i])) {
        cache.pixels[i] = SurfacePixel();
        cache.near_object.push_back(static_cast<std::uint32_t>(i));
      }
    cache.distance = view.distance;
    cache.elevation = view.elevation_deg;
    cache.roll = view.roll_deg;
    cache.table = view.table_half_size;
    cache.light_cam = light_cam;
  }
  std::vector<SurfacePixel> out = cache.pixels;
  for (std::uint32_t i : cache.near_object) castPixel(i, true, out[i]);
  return out;
}

Cloud builtinBenchmarkView() {
  SceneView view;
  view.turntable_deg = 30.0;
  return TofViewRenderer(makeMugMesh()).render(view);
}

}  // namespace keyturn::sim
