#pragma once
// The studio's Reconstruct: the captured object's views in the capture's dataset (all its
// elevations) joined into its model by the library keyturn reconstruct calls
// (reconstruction/reconstruction.h), on a background job; the mesh then shown in the 3D view and
// written beside the dataset, in DATASET.reconstruction/CLASS/INSTANCE/ (cloud.ply, mesh.ply,
// poses.txt, report.json: the CLI's files).
#include <QObject>
#include <QString>
#include <string>

namespace keyturn::studio {

class BackgroundJob;
class CapturePanel;
class CloudView;

class ReconstructController : public QObject {
  Q_OBJECT
 public:
  ReconstructController(CapturePanel* panel, CloudView* cloud, BackgroundJob& job, QObject* parent = nullptr);

  // The reconstruction folder of the capture panel's object ("" without a dataset or object).
  std::string folder() const;
  void setPoissonDepth(int depth) { poisson_depth_ = depth; }  // 0: the library's default

 signals:
  void reconstructed(const QString& folder, const QString& summary);  // the mesh is in the 3D view
  void failed(const QString& error);

 public slots:
  void reconstruct();

 private:
  CapturePanel* panel_;
  CloudView* cloud_;
  BackgroundJob& job_;
  int poisson_depth_ = 0;
};

}  // namespace keyturn::studio
