#pragma once
// One object added to a trained model from its mesh (keyturn enroll, the studio's Enroll…): its
// training views rendered through the simulated cameras by the built-in model's recipe
// (object_simulation.h), described with the model's parameters, and the model retrained with them
// (learning/model_enrollment.h). The CLI and the studio call this one function.
#include <functional>
#include <string>

#include "keyturn/learning/feature_cache.h"
#include "keyturn/learning/model_enrollment.h"
#include "keyturn/rig/object_simulation.h"

namespace keyturn::rig {

struct ObjectEnrollment {
  ObjectSimulation simulation;  // the object (class, instance, mesh) and the recipe; dir "" = out + ".views"
  std::string model;            // the model folder it is added to
  std::string out;              // the new model's folder (may be `model`)
  bool keep_views = false;      // else the rendered views are removed once the model is written
  int jobs = 0;                 // parallel views when describing (0: all cores)
};

// What the enrollment says as it goes; every member may be left as it is.
struct EnrollmentProgress {
  // Before rendering: the views to render, the class the object gets, the folder they go to.
  std::function<void(std::size_t views, const std::string& label, const std::string& dir)> rendering =
      [](std::size_t, const std::string&, const std::string&) {};
  std::function<void()> view_rendered = [] {};
  std::function<void()> rendered = [] {};
  learning::DescribeProgress* describe = nullptr;  // each camera's dataset in turn
  // Before retraining: the model as it was and the new views described.
  std::function<void(const learning::Model& before, std::size_t new_views)> retraining =
      [](const learning::Model&, std::size_t) {};
};

struct EnrolledObject {
  std::string label;  // the object's class in the new model
  learning::Model before;
  learning::Enrollment enrollment;
  double render_s = 0, describe_s = 0, train_s = 0;
};

// A mesh file, or a reconstruction folder's mesh.ply. Throws keyturn::Error naming `input` when
// it is neither.
std::string enrollmentMesh(const std::string& input);

// Writes the new model to request.out. Everything that can refuse (the model, the class already
// in it, the mesh) is checked before the minutes of rendering; throws keyturn::Error.
EnrolledObject enrollObject(ObjectEnrollment request, const EnrollmentProgress& progress = EnrollmentProgress());

}  // namespace keyturn::rig
