#pragma once
// The 3D view (VTK): the filtered cloud coloured by depth, the ISS keypoints as
// red spheres, and on demand the view's geodesic paths (centroid → keypoints); or, in its place,
// a reconstructed model's mesh (Reconstruct), until the live cloud is asked for again.
#include <Eigen/Core>
#include <array>
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

  // A model's surface (its own frame, z up) replaces the live cloud, looked at from above its side.
  void setModel(const std::vector<Eigen::Vector3f>& vertices, const std::vector<Eigen::Vector3i>& triangles);
  void setModelShown(bool shown);  // false: the live cloud again
  bool modelShown() const { return model_shown_; }
  int modelVertices() const;
  int modelTriangles() const;
  std::array<double, 6> modelBounds() const;  // x min, x max, y min, y max, z min, z max (metres)

 private:
  QVTKOpenGLStereoWidget* widget_ = nullptr;
  vtkSmartPointer<vtkGenericOpenGLRenderWindow> window_;
  vtkSmartPointer<vtkRenderer> renderer_;
  vtkSmartPointer<vtkPolyData> cloud_, keypoints_, paths_, model_;
  vtkSmartPointer<vtkPolyDataMapper> cloud_mapper_;
  vtkSmartPointer<vtkActor> cloud_actor_, keypoints_actor_, paths_actor_, model_actor_;
  bool model_shown_ = false;
  void lookAtModel();
  bool camera_set_ = false;
  int shown_points_ = 0;
};

}  // namespace keyturn::studio
