#include "keyturn/rig/dataset_simulation.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>

#include "keyturn/core/error.h"
#include "keyturn/core/fnv1a.h"
#include "keyturn/rig/simulated_rig.h"
#include "keyturn/sim/mesh.h"
#include "keyturn/sim/tof_view.h"
#include "keyturn/dataset/dataset_layout.h"

namespace keyturn::rig {
namespace {

CaptureOptions baseOptions(const DatasetSimulation& s) {
  CaptureOptions base;
  base.step_deg = s.step_deg;
  base.settle_s = 0.0;       // the simulated table reports only where it is
  // The simulated SR4000 renders when asked, so its first frame is at the new angle. The OpenNI2
  // camera's frames run free: the newest may predate the move, and so may the one being rendered
  // while the table arrived. The frame after both is the first at the angle (without discarding,
  // a 90° view was the 0° frame again).
  base.discard_frames = s.camera == SimulatedCamera::OpenNi2 ? 2 : 0;
  base.stop = s.stop;
  return base;
}

// FNV-1a over the view's identity (unit-separated fields), keyed by the seed: a draw that depends
// on nothing else.
std::uint64_t viewHash(std::uint64_t seed, const dataset::ViewKey& v) {
  char angle[32];
  std::snprintf(angle, sizeof angle, "%.3f", v.commanded_deg);
  const std::string identity = v.cls + '\x1f' + v.instance + '\x1f' + v.elevation + '\x1f' + angle + '\x1f';
  return fnv1a(identity, 1469598103934665603ull ^ seed);
}

CaptureOptions viewOptions(const CaptureOptions& base, const dataset::ObjectRow& obj, double el, const std::string& label) {
  CaptureOptions o = base;
  o.cls = obj.cls;
  o.instance = obj.instance;
  o.elevation_deg = el;
  o.elevation_label = label;
  return o;
}

std::string elevationLabel(double el) { return std::to_string(static_cast<int>(std::lround(el))); }

// What every simulated rig of a dataset shares: its folder, the object's mesh, the camera and its noise.
SimulatedRigOptions rigOptions(const DatasetSimulation& s, const dataset::ObjectRow& obj) {
  SimulatedRigOptions so;
  so.dir = dataset::datasetPath(s.out, dataset::kSimulatorFolder);
  so.camera.mesh = obj.mesh;
  so.camera.seed = s.seed;
  so.fast = true;
  so.openni2 = s.camera == SimulatedCamera::OpenNi2;
  // The same dataset on every run, whichever frame is taken: the OpenNI2 camera's frames come on
  // its own thread, so its noise is drawn per pose. The SR4000's come in capture order and keep
  // their per-frame draws (the datasets and models made before the SR4000 honoured noise_per_pose).
  so.camera.noise_per_pose = so.openni2;
  return so;
}

// Without jitter: one rig per object and elevation, the whole turn captured in one sequence.
void simulateSequences(const DatasetSimulation& s, dataset::Dataset& dataset, const CaptureOptions& base, CaptureReport& total,
                       const std::function<void()>& view_done) {
  for (const auto& obj : s.objects) {
    for (double el : s.elevations) {
      if (s.stop && *s.stop) return;
      SimulatedRigOptions so = rigOptions(s, obj);
      so.camera.elevation_deg = el;
      SimulatedRig simrig = openSimulatedRig(so);
      CaptureOptions o = viewOptions(base, obj, el, elevationLabel(el));
      o.camera_from_turntable_zero = simrig.camera_from_turntable;
      const auto rep = runCapture(*simrig.camera, *simrig.turntable, dataset, o, [&](const CaptureProgress&) {
        if (view_done) view_done();
      });
      total.written += rep.written;
      total.skipped += rep.skipped;
      total.redos += rep.redos;
    }
  }
}

// One jittered view: a rig opened with the view's draw, capturing that view only.
CaptureReport captureJitteredView(const DatasetSimulation& s, dataset::Dataset& dataset, const CaptureOptions& base,
                                  const dataset::ObjectRow& obj, const sim::Mesh& mesh, const dataset::ViewKey& key, double el) {
  const JitteredView draw = drawJitter(s.jitter, s.seed, key, el);
  SimulatedRigOptions so = rigOptions(s, obj);
  so.camera.elevation_deg = draw.elevation_deg;
  so.camera.distance = sim::operatorDistance(sim::scaledMesh(mesh, draw.scale)) * draw.distance_scale;
  so.camera.scale = draw.scale;
  so.camera.roll_deg = draw.roll_deg;
  so.camera.seed = viewHash(s.seed, key);  // each view its own noise
  SimulatedRig simrig = openSimulatedRig(so);
  if (draw.integration > 0) {
    drivers::TofSettings settings = simrig.camera->settings();
    settings.auto_exposure.enabled = false;
    settings.integration_time = static_cast<std::uint8_t>(draw.integration);
    simrig.camera->configure(settings);
  }
  CaptureOptions o = viewOptions(base, obj, draw.elevation_deg, key.elevation);
  o.start_deg = key.commanded_deg;
  o.range_deg = base.step_deg;  // this view only
  o.camera_from_turntable_zero = simrig.camera_from_turntable;
  return runCapture(*simrig.camera, *simrig.turntable, dataset, o);
}

// With jitter: every view its own rig (captureJitteredView); views already there are skipped unopened.
void simulateJitteredViews(const DatasetSimulation& s, dataset::Dataset& dataset, const CaptureOptions& base,
                           CaptureReport& total, const std::function<void()>& view_done) {
  for (const auto& obj : s.objects) {
    const sim::Mesh mesh = sim::loadMeshOrBuiltin(obj.mesh);
    for (double el : s.elevations)
      for (double angle : sequenceAngles(base)) {
        if (s.stop && *s.stop) return;
        const dataset::ViewKey key{obj.cls, obj.instance, elevationLabel(el), angle};
        if (dataset.has(key)) {
          ++total.skipped;
        } else {
          const CaptureReport rep = captureJitteredView(s, dataset, base, obj, mesh, key, el);
          total.written += rep.written;
          total.skipped += rep.skipped;
          total.redos += rep.redos;
        }
        if (view_done) view_done();
      }
  }
}

}  // namespace

void ViewJitter::check() const {
  if (!(distance >= 0 && distance < 0.5)) throw Error("jitter: the distance fraction must be in [0, 0.5)");
  if (!(scale >= 0 && scale < 0.5)) throw Error("jitter: the scale fraction must be in [0, 0.5)");
  if (!(elevation_deg >= 0 && elevation_deg <= 20)) throw Error("jitter: the elevation must be within 0–20°");
  if (!(tilt_deg >= 0 && tilt_deg <= 20)) throw Error("jitter: the tilt must be within 0–20°");
  if (integration_max > 0 && !(integration_min >= 1 && integration_min <= integration_max && integration_max <= 255))
    throw Error("jitter: the integration codes must satisfy 1 <= MIN <= MAX <= 255");
}

void ViewJitter::check(SimulatedCamera camera) const {
  check();
  if (camera != SimulatedCamera::Sr4000 && integration_max > 0)
    throw Error(std::string("jitter: integration time is the SR4000's; the ") + simulatedCameraName(camera) +
                " camera has none");
}

SimulatedCamera parseSimulatedCamera(const std::string& name) {
  if (name == "sr4000") return SimulatedCamera::Sr4000;
  if (name == "openni2") return SimulatedCamera::OpenNi2;
  throw Error("simulated camera '" + name + "': expected sr4000 (time of flight) or openni2 (Kinect-class structured light)");
}

std::vector<SimulatedCamera> parseSimulatedCameras(const std::string& list) {
  std::vector<SimulatedCamera> out;
  std::size_t at = 0;
  while (at <= list.size()) {
    const std::size_t comma = std::min(list.find(',', at), list.size());
    out.push_back(parseSimulatedCamera(list.substr(at, comma - at)));
    at = comma + 1;
  }
  return out;
}

const char* simulatedCameraName(SimulatedCamera camera) {
  return camera == SimulatedCamera::OpenNi2 ? "openni2" : "sr4000";
}

JitteredView drawJitter(const ViewJitter& j, std::uint64_t seed, const dataset::ViewKey& view, double elevation_deg) {
  std::mt19937_64 rng(viewHash(seed, view));
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  JitteredView d;
  d.distance_scale = 1.0 + j.distance * u(rng);
  d.elevation_deg = elevation_deg + j.elevation_deg * u(rng);
  d.roll_deg = j.tilt_deg * u(rng);
  if (j.integration_max > 0)
    d.integration = std::uniform_int_distribution<int>(j.integration_min, j.integration_max)(rng);
  d.scale = 1.0 + j.scale * u(rng);  // drawn last: the other draws do not depend on it
  return d;
}

void DatasetSimulation::checkMeshes(const std::string& list_path) const {
  for (const auto& o : objects)
    if (!std::filesystem::exists(o.mesh)) throw Error(list_path + ": " + o.cls + "/" + o.instance + ": no mesh at " + o.mesh);
}

std::size_t DatasetSimulation::views() const {
  return sequenceAngles(baseOptions(*this)).size() * objects.size() * elevations.size();
}

CaptureReport simulateDataset(const DatasetSimulation& s, const std::function<void()>& view_done) {
  s.jitter.check(s.camera);
  dataset::Dataset dataset(s.out);
  const CaptureOptions base = baseOptions(s);
  CaptureReport total;
  if (s.jitter.any()) simulateJitteredViews(s, dataset, base, total, view_done);
  else simulateSequences(s, dataset, base, total, view_done);
  total.stopped = s.stop && *s.stop;
  return total;
}

}  // namespace keyturn::rig
