// keyturn.reconstruct: the posed views of one object joined into its model by the library keyturn
// reconstruct calls (reconstruction/reconstruction.h), given back as numpy arrays that Open3D
// takes (keyturn.to_open3d makes its TriangleMesh) and savable as the CLI's folder.
#include <pybind11/stl.h>

#include <cstdio>
#include <optional>

#include "bindings.h"
#include "keyturn/core/pose_list.h"
#include "keyturn/reconstruction/reconstruction.h"

namespace keyturn::python {
namespace {

struct PyReconstruction {
  reconstruction::Reconstruction r;
  std::string source;
};

template <typename Scalar, typename Vec>
py::array_t<Scalar> rows(const std::vector<Vec>& v) {
  constexpr int n = Vec::RowsAtCompileTime;
  py::array_t<Scalar> a({static_cast<py::ssize_t>(v.size()), static_cast<py::ssize_t>(n)});
  auto m = a.template mutable_unchecked<2>();
  for (std::size_t i = 0; i < v.size(); ++i)
    for (int j = 0; j < n; ++j) m(static_cast<py::ssize_t>(i), j) = static_cast<Scalar>(v[i][j]);
  return a;
}

std::string pathOf(const py::object& p) { return py::str(py::module_::import("os").attr("fspath")(p)); }

PyReconstruction reconstructViews(const py::object& source, const std::optional<std::string>& object,
                                  const std::optional<std::vector<double>>& elevations, bool refine, bool filter,
                                  std::optional<int> poisson_depth, const std::string& surface, bool free_tilt,
                                  const py::object& out) {
  PyReconstruction result;
  result.source = pathOf(source);
  requireFile(result.source);
  reconstruction::ViewSelection selection;
  if (object) selection.object = *object;
  for (double e : elevations.value_or(std::vector<double>{})) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", e);  // the dataset's elevation labels, as the CLI reads them
    selection.elevations.emplace_back(text);
  }
  reconstruction::ReconstructionOptions options;
  options.registration.refine = refine;
  options.filter = filter;
  options.registration.level_on_support = !free_tilt;
  if (surface == "auto") options.surface = reconstruction::SurfaceChoice::Auto;
  else if (surface == "poisson") options.surface = reconstruction::SurfaceChoice::Poisson;
  else if (surface == "tsdf") options.surface = reconstruction::SurfaceChoice::Tsdf;
  else throw py::value_error("reconstruct: surface must be 'auto', 'poisson' or 'tsdf', not '" + surface + "'");
  if (poisson_depth) {
    if (*poisson_depth < 5 || *poisson_depth > 12)
      throw py::value_error("reconstruct: poisson_depth must be within 5 and 12, not " + std::to_string(*poisson_depth));
    options.poisson.depth = *poisson_depth;
  }
  const std::optional<std::string> dir = out.is_none() ? std::nullopt : std::optional<std::string>(pathOf(out));
  py::gil_scoped_release release;
  auto views = reconstruction::posedViews(result.source, PoseReadOptions(), selection);
  result.r = reconstruction::reconstruct(std::move(views), options);
  if (dir) reconstruction::writeReconstruction(*dir, result.r, result.source);
  return result;
}

}  // namespace

void bindReconstruct(py::module_& m) {
  py::class_<PyReconstruction>(m, "Reconstruction",
                               "One object's model: its surface, fused points and refined poses (keyturn.reconstruct)")
      .def_property_readonly("vertices", [](const PyReconstruction& p) { return rows<float>(p.r.mesh.vertices); },
                             "The surface's vertices, V × 3 float32 (metres, the views' common frame)")
      .def_property_readonly("triangles", [](const PyReconstruction& p) { return rows<std::int32_t>(p.r.mesh.triangles); },
                             "The surface's triangles, T × 3 int32 indices into vertices")
      .def_property_readonly("points", [](const PyReconstruction& p) { return rows<float>(p.r.cloud.points); },
                             "The fused cloud, N × 3 float32")
      .def_property_readonly("normals", [](const PyReconstruction& p) { return rows<float>(p.r.cloud.normals); },
                             "The fused cloud's normals, N × 3 float32")
      .def_property_readonly("poses", [](const PyReconstruction& p) {
            py::array_t<double> a({static_cast<py::ssize_t>(p.r.views.size()), py::ssize_t(4), py::ssize_t(4)});
            auto m = a.mutable_unchecked<3>();
            for (std::size_t i = 0; i < p.r.views.size(); ++i)
              for (int r = 0; r < 4; ++r)
                for (int c = 0; c < 4; ++c) m(static_cast<py::ssize_t>(i), r, c) = p.r.views[i].world_from_view(r, c);
            return a;
          }, "Each view's refined pose (common frame ← view), K × 4 × 4 float64")
      .def_property_readonly("views", [](const PyReconstruction& p) {
            std::vector<std::string> files;
            for (const auto& v : p.r.views) files.push_back(v.file);
            return files;
          }, "The views' files, in the order of poses")
      .def_property_readonly("model", [](const PyReconstruction& p) { return std::string(reconstruction::poseModelName(p.r.model)); },
                             "The pose model refined: 'turntable' or 'free'")
      .def_property_readonly("surface", [](const PyReconstruction& p) {
            return std::string(p.r.surface == reconstruction::SurfaceChoice::Tsdf ? "tsdf" : "poisson");
          }, "How the surface was made: 'tsdf' or 'poisson'")
      .def_property_readonly("report", [](const PyReconstruction& p) {
            return py::module_::import("json").attr("loads")(reconstruction::reconstructionJson(p.r, p.source));
          }, "report.json's contents: per-view residuals before and after, the axes, the stages' times")
      .def_property_readonly("summary", [](const PyReconstruction& p) { return reconstruction::reconstructionSummary(p.r); },
                             "The lines keyturn reconstruct prints")
      .def("save", [](const PyReconstruction& p, const py::object& out) {
            const std::string dir = pathOf(out);
            py::gil_scoped_release release;
            reconstruction::writeReconstruction(dir, p.r, p.source);
          }, py::arg("out"), "Writes OUT/cloud.ply, mesh.ply, poses.txt and report.json, as keyturn reconstruct does")
      .def("__repr__", [](const PyReconstruction& p) {
        return "<keyturn.Reconstruction of " + std::to_string(p.r.views.size()) + " views: " +
               std::to_string(p.r.mesh.vertices.size()) + " vertices, " + std::to_string(p.r.mesh.triangles.size()) +
               " triangles, " + std::to_string(p.r.cloud.points.size()) + " points>";
      });

  m.def("reconstruct", &reconstructViews, py::arg("source"), py::kw_only(), py::arg("object") = py::none(),
        py::arg("elevations") = py::none(), py::arg("refine") = true, py::arg("filter") = true,
        py::arg("poisson_depth") = py::none(), py::arg("surface") = "auto", py::arg("free_tilt") = false,
        py::arg("out") = py::none(),
        "The views of one object joined into its model, as `keyturn reconstruct` joins them: SOURCE a calibrated "
        "dataset or a pose file; object 'CLASS/INSTANCE' when the dataset holds several; elevations a subset of the "
        "dataset's; refine=False keeps the poses as given; surface 'auto' (TSDF when every view is an organized "
        "depth frame, else Poisson), 'poisson' or 'tsdf'; free_tilt=True refines each rig camera's tilt from the "
        "object, not the support plane; out also writes the CLI's folder. Returns a "
        "keyturn.Reconstruction (keyturn.to_open3d makes it an Open3D TriangleMesh). Raises keyturn.Error with "
        "one line for no poses, views of two objects, a single view or views that do not overlap.");
}

}  // namespace keyturn::python
