#pragma once
// The 3D view (VTK): the filtered cloud coloured by depth, the ISS keypoints as
// red spheres, and on demand the view's geodesic paths (centroid → keypoints).
#include <Eigen/Core>
#include <QWidget>
#include <vector>

#include <vtkSmartPointer.h>

class QVTKOpenGLStereoWidget;
class vtkActor;
class vtkGenericOpenGLRenderWindow;
class vtkPolyData;
class vtkPolyDataMapper;
class vtkRenderer;

namespace keyturn::studio {

class CloudView : public QWidget {
  Q_OBJECT
 public:
  explicit CloudView(QWidget* parent = nullptr);
  ~CloudView() override;
  void show(const std::vector<Eigen::Vector3f>& points, const std::vector<Eigen::Vector3f>& keypoints,
            const std::vector<std::vector<Eigen::Vector3f>>& paths);
  void resetCamera();
  int shownPoints() const { return shown_points_; }

 private:
  QVTKOpenGLStereoWidget* widget_ = nullptr;
  vtkSmartPointer<vtkGenericOpenGLRenderWindow> window_;
  vtkSmartPointer<vtkRenderer> renderer_;
  vtkSmartPointer<vtkPolyData> cloud_, keypoints_, paths_;
  vtkSmartPointer<vtkPolyDataMapper> cloud_mapper_;
  bool camera_set_ = false;
  int shown_points_ = 0;
};

}  // namespace keyturn::studio
