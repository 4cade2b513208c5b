#pragma once
// The studio's Enroll…: the object last reconstructed (its mesh.ply) added to the model recognition
// runs, by the library keyturn enroll calls (rig/object_enrollment.h), on a background job. The new
// model goes beside the current one (MODEL+INSTANCE); recognition then switches to it, so the live
// verdict can name the object.
#include <QObject>
#include <QString>
#include <functional>
#include <string>
#include <vector>

#include "keyturn/rig/dataset_simulation.h"

class QWidget;

namespace keyturn::studio {

class BackgroundJob;

// Where the object's training views come from: the built-in model's recipe unless changed.
struct EnrollRecipe {
  std::vector<rig::SimulatedCamera> cameras = {rig::SimulatedCamera::Sr4000, rig::SimulatedCamera::OpenNi2};
  std::vector<double> elevations = {30, 45, 60};
  double step_deg = 5;
};

// The folder beside `model` the enrolled model goes to: MODEL+INSTANCE (the instance's characters
// other than letters, digits, '-', '_' and '.' as '_'), then -2, -3 … when that one exists.
std::string enrolledModelFolder(const std::string& model, const std::string& instance);

class EnrollController : public QObject {
  Q_OBJECT
 public:
  // `mesh_folder` gives the reconstruction to enroll, `model` the model recognition runs ("" none),
  // `object` the capture's class and instance (the dialog's suggestion).
  EnrollController(BackgroundJob& job, QWidget* dialog_parent, std::function<std::string()> mesh_folder,
                   std::function<QString()> model, std::function<std::pair<QString, QString>()> object,
                   QObject* parent = nullptr);
  void setRecipe(const EnrollRecipe& recipe) { recipe_ = recipe; }

 signals:
  void enrolled(const QString& model, const QString& summary);  // switch recognition to `model`
  void failed(const QString& error);

 public slots:
  void enroll();  // asks the class and instance, then runs

 private:
  BackgroundJob& job_;
  QWidget* dialog_parent_;
  std::function<std::string()> mesh_folder_;
  std::function<QString()> model_;
  std::function<std::pair<QString, QString>()> object_;
  EnrollRecipe recipe_;
};

}  // namespace keyturn::studio
