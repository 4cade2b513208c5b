#include "keyturn/rig/dataset_simulation.h"

#include <cmath>
#include <filesystem>

#include "keyturn/core/error.h"
#include "keyturn/rig/simulated_rig.h"

namespace keyturn::rig {
namespace {

CaptureOptions baseOptions(const DatasetSimulation& s) {
  CaptureOptions base;
  base.step_deg = s.step_deg;
  base.settle_s = 0.0;       // the simulated table reports only where it is
  base.discard_frames = 0;   // and the simulated sensor needs no warm-up frames
  base.stop = s.stop;
  return base;
}

}  // namespace

void DatasetSimulation::checkMeshes(const std::string& list_path) const {
  for (const auto& o : objects)
    if (!std::filesystem::exists(o.mesh)) throw Error(list_path + ": " + o.cls + "/" + o.instance + ": no mesh at " + o.mesh);
}

std::size_t DatasetSimulation::views() const {
  return sequenceAngles(baseOptions(*this)).size() * objects.size() * elevations.size();
}

CaptureReport simulateDataset(const DatasetSimulation& s, const std::function<void()>& view_done) {
  Dataset dataset(s.out);
  const CaptureOptions base = baseOptions(s);
  CaptureReport total;
  for (const auto& obj : s.objects) {
    for (double el : s.elevations) {
      if (s.stop && *s.stop) break;
      SimulatedRigOptions so;
      so.dir = s.out + "/.sim";
      so.camera.mesh = obj.mesh;
      so.camera.elevation_deg = el;
      so.camera.seed = s.seed;
      so.fast = true;
      SimulatedRig simrig = openSimulatedRig(so);
      CaptureOptions o = base;
      o.cls = obj.cls;
      o.instance = obj.instance;
      o.elevation_deg = el;
      o.elevation_label = std::to_string(static_cast<int>(std::lround(el)));
      o.camera_from_turntable_zero = simrig.camera_from_turntable;
      const auto rep = runCapture(*simrig.camera, *simrig.turntable, dataset, o, [&](const CaptureProgress&) {
        if (view_done) view_done();
      });
      total.written += rep.written;
      total.skipped += rep.skipped;
      total.redos += rep.redos;
    }
  }
  total.stopped = s.stop && *s.stop;
  return total;
}

}  // namespace keyturn::rig
