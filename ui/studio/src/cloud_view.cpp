#include "cloud_view.h"

#include <QVBoxLayout>
#include <QVTKOpenGLStereoWidget.h>
#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkFloatArray.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkLookupTable.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>

namespace keyturn::studio {
namespace {

vtkSmartPointer<vtkActor> actorFor(vtkPolyData* data, vtkSmartPointer<vtkPolyDataMapper>* mapper_out = nullptr) {
  auto mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
  mapper->SetInputData(data);
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  if (mapper_out) *mapper_out = mapper;
  return actor;
}

void setVertices(vtkPolyData* data, const std::vector<Eigen::Vector3f>& pts) {
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataTypeToFloat();
  points->SetNumberOfPoints(static_cast<vtkIdType>(pts.size()));
  auto verts = vtkSmartPointer<vtkCellArray>::New();
  for (std::size_t i = 0; i < pts.size(); ++i) {
    points->SetPoint(static_cast<vtkIdType>(i), pts[i].x(), pts[i].y(), pts[i].z());
    const vtkIdType id = static_cast<vtkIdType>(i);
    verts->InsertNextCell(1, &id);
  }
  data->SetPoints(points);
  data->SetVerts(verts);
}

}  // namespace

CloudView::CloudView(QWidget* parent) : QWidget(parent) {
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  widget_ = new QVTKOpenGLStereoWidget(this);
  window_ = vtkSmartPointer<vtkGenericOpenGLRenderWindow>::New();
  widget_->setRenderWindow(window_);
  layout->addWidget(widget_);
  setMinimumHeight(240);
  renderer_ = vtkSmartPointer<vtkRenderer>::New();
  renderer_->SetBackground(0.10, 0.11, 0.13);
  renderer_->SetBackground2(0.22, 0.24, 0.28);
  renderer_->GradientBackgroundOn();
  window_->AddRenderer(renderer_);

  cloud_ = vtkSmartPointer<vtkPolyData>::New();
  cloud_actor_ = actorFor(cloud_, &cloud_mapper_);
  auto& cloud_actor = cloud_actor_;
  auto lut = vtkSmartPointer<vtkLookupTable>::New();
  lut->SetHueRange(0.6, 0.0);  // near blue → far red, as the distance image's turbo map runs
  lut->Build();
  cloud_mapper_->SetLookupTable(lut);
  cloud_mapper_->SetScalarModeToUsePointData();
  cloud_actor->GetProperty()->SetPointSize(3);
  renderer_->AddActor(cloud_actor);

  keypoints_ = vtkSmartPointer<vtkPolyData>::New();
  keypoints_actor_ = actorFor(keypoints_);
  auto& kp_actor = keypoints_actor_;
  kp_actor->GetProperty()->SetColor(1.0, 0.15, 0.15);
  kp_actor->GetProperty()->SetPointSize(11);
  kp_actor->GetProperty()->SetRenderPointsAsSpheres(true);
  renderer_->AddActor(kp_actor);

  paths_ = vtkSmartPointer<vtkPolyData>::New();
  paths_actor_ = actorFor(paths_);
  auto& path_actor = paths_actor_;
  path_actor->GetProperty()->SetColor(1.0, 0.85, 0.1);
  path_actor->GetProperty()->SetLineWidth(2.5);
  renderer_->AddActor(path_actor);

  model_ = vtkSmartPointer<vtkPolyData>::New();
  model_actor_ = actorFor(model_);
  model_actor_->GetProperty()->SetColor(0.80, 0.78, 0.70);
  model_actor_->GetProperty()->SetSpecular(0.2);
  model_actor_->VisibilityOff();
  renderer_->AddActor(model_actor_);
}

CloudView::~CloudView() = default;

void CloudView::show(const std::vector<Eigen::Vector3f>& points, const std::vector<Eigen::Vector3f>& keypoints,
                     const std::vector<std::vector<Eigen::Vector3f>>& paths) {
  setVertices(cloud_, points);
  auto depth = vtkSmartPointer<vtkFloatArray>::New();
  depth->SetNumberOfValues(static_cast<vtkIdType>(points.size()));
  float lo = 1e9f, hi = -1e9f;
  for (std::size_t i = 0; i < points.size(); ++i) {
    depth->SetValue(static_cast<vtkIdType>(i), points[i].z());
    lo = std::min(lo, points[i].z());
    hi = std::max(hi, points[i].z());
  }
  cloud_->GetPointData()->SetScalars(depth);
  if (!points.empty()) cloud_mapper_->SetScalarRange(lo, hi);
  cloud_->Modified();
  setVertices(keypoints_, keypoints);
  keypoints_->Modified();

  auto pts = vtkSmartPointer<vtkPoints>::New();
  auto lines = vtkSmartPointer<vtkCellArray>::New();
  for (const auto& path : paths) {
    std::vector<vtkIdType> ids;
    for (const auto& p : path) ids.push_back(pts->InsertNextPoint(p.x(), p.y(), p.z()));
    if (ids.size() >= 2) lines->InsertNextCell(static_cast<vtkIdType>(ids.size()), ids.data());
  }
  paths_->SetPoints(pts);
  paths_->SetLines(lines);
  paths_->Modified();
  shown_points_ = static_cast<int>(points.size());
  if (!camera_set_ && !points.empty()) resetCamera();
  window_->Render();
}

void CloudView::setModel(const std::vector<Eigen::Vector3f>& vertices, const std::vector<Eigen::Vector3i>& triangles) {
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataTypeToFloat();
  points->SetNumberOfPoints(static_cast<vtkIdType>(vertices.size()));
  for (std::size_t i = 0; i < vertices.size(); ++i)
    points->SetPoint(static_cast<vtkIdType>(i), vertices[i].x(), vertices[i].y(), vertices[i].z());
  auto polys = vtkSmartPointer<vtkCellArray>::New();
  for (const auto& t : triangles) {
    const vtkIdType ids[3] = {t[0], t[1], t[2]};
    polys->InsertNextCell(3, ids);
  }
  model_->SetPoints(points);
  model_->SetPolys(polys);
  model_->Modified();
  setModelShown(true);
}

void CloudView::setModelShown(bool shown) {
  model_shown_ = shown;
  model_actor_->SetVisibility(shown);
  for (vtkActor* a : {cloud_actor_.Get(), keypoints_actor_.Get(), paths_actor_.Get()}) a->SetVisibility(!shown);
  if (shown) lookAtModel();
  else resetCamera();
}

int CloudView::modelVertices() const { return static_cast<int>(model_->GetNumberOfPoints()); }
int CloudView::modelTriangles() const { return static_cast<int>(model_->GetNumberOfPolys()); }

std::array<double, 6> CloudView::modelBounds() const {
  std::array<double, 6> b{};
  model_->GetBounds(b.data());
  return b;
}

void CloudView::lookAtModel() {
  // The model's frame has z up: look at it from its side, 35° above, as the rig's camera does.
  const auto b = modelBounds();
  const double cx = (b[0] + b[1]) / 2, cy = (b[2] + b[3]) / 2, cz = (b[4] + b[5]) / 2;
  vtkCamera* cam = renderer_->GetActiveCamera();
  cam->SetFocalPoint(cx, cy, cz);
  cam->SetPosition(cx, cy - 0.82, cz + 0.57);
  cam->SetViewUp(0, 0, 1);
  renderer_->ResetCamera();
  window_->Render();
}

void CloudView::resetCamera() {
  if (model_shown_) {
    lookAtModel();
    return;
  }
  // The camera's own viewpoint: optical frame, looking along +z with +y down.
  vtkCamera* cam = renderer_->GetActiveCamera();
  cam->SetPosition(0, 0, 0);
  cam->SetFocalPoint(0, 0, 1);
  cam->SetViewUp(0, -1, 0);
  renderer_->ResetCamera();
  camera_set_ = true;
  window_->Render();
}

}  // namespace keyturn::studio
