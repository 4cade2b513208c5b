#pragma once
// An SR4K-D style dataset generated on the simulated rig (keyturn simulate): the
// real capture path (drivers, Modbus, libmesasr-sim) for every object of a list
// at every elevation, with simulated motion and settling shrunk far below real
// time. Resumable like a capture: views already in the dataset are skipped.
#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "keyturn/rig/capture.h"
#include "keyturn/rig/object_list.h"

namespace keyturn::rig {

struct DatasetSimulation {
  std::string out;                  // the dataset folder (its rig's files in OUT/.sim)
  std::vector<ObjectRow> objects;
  std::vector<double> elevations;   // degrees; labelled by their whole degrees
  double step_deg = 5;
  std::uint64_t seed = 1;           // sensor noise
  std::atomic<bool>* stop = nullptr;  // set (e.g. by Ctrl-C) to stop after the current view

  // Throws keyturn::Error naming list_path and the object whose mesh is missing.
  void checkMeshes(const std::string& list_path) const;
  std::size_t views() const;        // in all, objects × elevations × angles
};

// Writes (or resumes) the dataset; view_done after every view written or skipped.
CaptureReport simulateDataset(const DatasetSimulation& simulation, const std::function<void()>& view_done = {});

}  // namespace keyturn::rig
