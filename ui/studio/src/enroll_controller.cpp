#include "enroll_controller.h"

#include <cctype>
#include <filesystem>
#include <memory>

#include "background_job.h"
#include "enroll_dialog.h"
#include "keyturn/rig/object_enrollment.h"

namespace keyturn::studio {
namespace {

namespace fs = std::filesystem;

// Describing's progress as the job's steps.
class DescribeSteps final : public learning::DescribeProgress {
 public:
  explicit DescribeSteps(BackgroundJob& job) : job_(job) {}
  void begin(std::size_t views) override { job_.stage(QObject::tr("describe"), static_cast<int>(views)); }
  void viewDone() override { job_.step(); }
  void end() override {}
  void note(const std::string&) override {}
  void warning(const std::string&) override {}

 private:
  BackgroundJob& job_;
};

}  // namespace

std::string enrolledModelFolder(const std::string& model, const std::string& instance) {
  std::string safe = instance;
  for (char& c : safe)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.')) c = '_';
  fs::path dir = fs::path(model);
  if (!dir.has_filename()) dir = dir.parent_path();  // "models/m/" names m
  const std::string base = dir.string() + "+" + safe;
  std::string out = base;
  std::error_code ec;
  for (int n = 2; fs::exists(out, ec); ++n) out = base + "-" + std::to_string(n);
  return out;
}

EnrollController::EnrollController(BackgroundJob& job, QWidget* dialog_parent, std::function<std::string()> mesh_folder,
                                   std::function<QString()> model, std::function<std::pair<QString, QString>()> object,
                                   QObject* parent)
    : QObject(parent), job_(job), dialog_parent_(dialog_parent), mesh_folder_(std::move(mesh_folder)),
      model_(std::move(model)), object_(std::move(object)) {}

void EnrollController::enroll() {
  const std::string folder = mesh_folder_();
  const std::string model = model_().trimmed().toStdString();
  std::error_code ec;
  if (job_.running()) {
    emit failed(tr("enroll: another job is running"));
    return;
  }
  if (folder.empty() || !fs::is_regular_file(fs::path(folder) / "mesh.ply", ec)) {
    emit failed(tr("enroll: reconstruct the captured object first (no %1)")
                    .arg(QString::fromStdString((fs::path(folder) / "mesh.ply").string())));
    return;
  }
  if (model.empty()) {
    emit failed(tr("enroll: load the model to add the object to first (Recognition → Load…)"));
    return;
  }
  const auto [cls, instance] = object_();
  EnrollDialog dialog(cls, instance, QString::fromStdString(model), dialog_parent_);
  if (dialog.exec() != QDialog::Accepted) return;

  rig::ObjectEnrollment request;
  rig::ObjectSimulation& sim = request.simulation;
  sim.object = {dialog.cls().toStdString(), dialog.instance().toStdString(), (fs::path(folder) / "mesh.ply").string()};
  sim.cameras = recipe_.cameras;
  sim.elevations = recipe_.elevations;
  sim.step_deg = recipe_.step_deg;
  request.model = model;
  request.out = enrolledModelFolder(model, sim.object.instance);
  auto result = std::make_shared<rig::EnrolledObject>();
  job_.start(
      tr("enroll"),
      [request, result](BackgroundJob& job) {
        DescribeSteps describe(job);
        rig::EnrollmentProgress progress;
        progress.rendering = [&job](std::size_t views, const std::string&, const std::string&) {
          job.stage(tr("render"), static_cast<int>(views));
        };
        progress.view_rendered = [&job] { job.step(); };
        progress.describe = &describe;
        progress.retraining = [&job](const learning::Model&, std::size_t) { job.stage(tr("retrain"), 0); };
        *result = rig::enrollObject(request, progress);
      },
      [this, request, result] {
        const QString out = QString::fromStdString(request.out);
        emit enrolled(out, tr("enrolled %1 from %2 views: %3 classes → %4")
                               .arg(QString::fromStdString(result->label))
                               .arg(result->enrollment.new_views)
                               .arg(result->enrollment.model.info.classes.size())
                               .arg(out));
      });
}

}  // namespace keyturn::studio
