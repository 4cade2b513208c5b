#include "reconstruct_controller.h"

#include <filesystem>
#include <memory>

#include "background_job.h"
#include "capture_panel.h"
#include "cloud_view.h"
#include "keyturn/reconstruction/reconstruction.h"

namespace keyturn::studio {

ReconstructController::ReconstructController(CapturePanel* panel, CloudView* cloud, BackgroundJob& job, QObject* parent)
    : QObject(parent), panel_(panel), cloud_(cloud), job_(job) {}

std::string ReconstructController::folder() const {
  const auto o = panel_->options();
  if (panel_->dataset().empty() || o.cls.empty() || o.instance.empty()) return "";
  return (std::filesystem::path(panel_->dataset() + ".reconstruction") / o.cls / o.instance).string();
}

void ReconstructController::reconstruct() {
  const std::string dataset = panel_->dataset();
  const auto capture = panel_->options();
  if (dataset.empty() || capture.cls.empty() || capture.instance.empty()) {
    emit failed(tr("reconstruct: choose the dataset and name the class and instance of the captured object"));
    return;
  }
  const std::string out = folder();
  reconstruction::ViewSelection selection;
  selection.object = capture.cls + "/" + capture.instance;
  reconstruction::ReconstructionOptions options;
  if (poisson_depth_ > 0) options.poisson.depth = poisson_depth_;
  auto result = std::make_shared<reconstruction::Reconstruction>();
  const bool started = job_.start(
      tr("reconstruct"),
      [=](BackgroundJob& job) {
        reconstruction::ReconstructionProgress progress;
        progress.stages.begin = [&job](const std::string& stage, std::size_t n) {
          job.stage(QString::fromStdString(stage), static_cast<int>(n));
        };
        progress.stages.step = [&job] { job.step(); };
        auto views = reconstruction::posedViews(dataset, PoseReadOptions(), selection);
        *result = reconstruction::reconstruct(std::move(views), options, progress);
        job.stage(tr("writing %1").arg(QString::fromStdString(out)), 0);
        reconstruction::writeReconstruction(out, *result, dataset);
      },
      [this, result, out] {
        cloud_->setModel(result->mesh.vertices, result->mesh.triangles);
        const QString summary = tr("reconstructed %1 views: %2 vertices, %3 triangles → %4")
                                    .arg(result->views.size())
                                    .arg(result->mesh.vertices.size())
                                    .arg(result->mesh.triangles.size())
                                    .arg(QString::fromStdString(out));
        emit reconstructed(QString::fromStdString(out), summary);
      });
  if (!started) emit failed(tr("reconstruct: another job is running"));
}

}  // namespace keyturn::studio
