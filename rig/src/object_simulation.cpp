#include "keyturn/rig/object_simulation.h"

#include <filesystem>

#include "keyturn/sim/mesh.h"

namespace keyturn::rig {

namespace {

DatasetSimulation cameraSimulation(const ObjectSimulation& s, SimulatedCamera camera) {
  DatasetSimulation d;
  d.out = s.datasetOf(camera);
  d.camera = camera;
  d.objects = {s.object};
  d.elevations = s.elevations;
  d.step_deg = s.step_deg;
  d.seed = s.seed;
  d.stop = s.stop;
  return d;
}

}  // namespace

std::size_t ObjectSimulation::views() const {
  std::size_t n = 0;
  for (SimulatedCamera c : cameras) n += cameraSimulation(*this, c).views();
  return n;
}

std::string ObjectSimulation::datasetOf(SimulatedCamera camera) const {
  return (std::filesystem::path(dir) / simulatedCameraName(camera)).string();
}

void ObjectSimulation::checkMesh() const { sim::loadMesh(object.mesh); }

CaptureReport simulateObject(const ObjectSimulation& s, const std::function<void()>& view_done) {
  s.checkMesh();  // a missing or broken mesh fails here, not inside the first camera's rig
  CaptureReport total;
  for (SimulatedCamera c : s.cameras) {
    if (s.stop && *s.stop) break;
    const CaptureReport rep = simulateDataset(cameraSimulation(s, c), view_done);
    total.written += rep.written;
    total.skipped += rep.skipped;
    total.redos += rep.redos;
  }
  return total;
}

}  // namespace keyturn::rig
