#pragma once
// One object's training views as the built-in model's recipe renders them (scripts/make-studio-model.sh,
// docs/results.md "Beyond the training conditions"): its mesh simulated through each simulated camera
// at each elevation, every step of the turntable, one dataset per camera with the same view ids
// (keyturn enroll renders a new object this way before adding it to a model).
#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "keyturn/dataset/object_list.h"
#include "keyturn/rig/dataset_simulation.h"

namespace keyturn::rig {

struct ObjectSimulation {
  dataset::ObjectRow object;  // category, instance and mesh file (metres, z up, base on z = 0)
  std::vector<SimulatedCamera> cameras = {SimulatedCamera::Sr4000, SimulatedCamera::OpenNi2};
  std::vector<double> elevations = {30, 45, 60};
  double step_deg = 5;
  std::uint64_t seed = 1;             // sensor noise, as keyturn simulate's default
  std::string dir;                    // DIR/<camera name>: one dataset per camera
  std::atomic<bool>* stop = nullptr;  // set to stop after the current view

  std::size_t views() const;  // in all, cameras × elevations × angles
  // Throws keyturn::Error naming the mesh when it is missing or unreadable.
  void checkMesh() const;
  // The dataset folder of one camera's views.
  std::string datasetOf(SimulatedCamera camera) const;
};

// Writes (or resumes) each camera's dataset; view_done after every view. The mesh is checked
// (checkMesh) before any view is rendered.
CaptureReport simulateObject(const ObjectSimulation& simulation, const std::function<void()>& view_done = {});

}  // namespace keyturn::rig
