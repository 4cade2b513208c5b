// keyturn.Cloud and keyturn.load_cloud: point clouds as numpy arrays, N × 3 or, organized,
// H × W × 3 with NaN where a pixel has no point; amplitude and confidence alongside.
#include <pybind11/stl.h>

#include "bindings.h"
#include "keyturn/core/cloud_io.h"

namespace keyturn::python {
namespace {

using FloatArray = py::array_t<float, py::array::c_style | py::array::forcecast>;

std::vector<py::ssize_t> layoutShape(const Cloud& c, bool xyz) {
  std::vector<py::ssize_t> shape;
  if (c.organized()) shape = {static_cast<py::ssize_t>(c.height), static_cast<py::ssize_t>(c.width)};
  else shape = {static_cast<py::ssize_t>(c.size())};
  if (xyz) shape.push_back(3);
  return shape;
}

py::object pointsArray(const Cloud& c) {
  py::array_t<float> a(layoutShape(c, true));
  float* out = a.mutable_data();
  for (std::size_t i = 0; i < c.points.size(); ++i)
    for (int k = 0; k < 3; ++k) out[3 * i + static_cast<std::size_t>(k)] = c.points[i][k];
  return std::move(a);
}

py::object channelArray(const Cloud& c, const std::vector<float>& v) {
  if (v.empty()) return py::none();
  py::array_t<float> a(layoutShape(c, false));
  std::copy(v.begin(), v.end(), a.mutable_data());
  return std::move(a);
}

std::string shapeText(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t i = 0; i < a.ndim(); ++i) s += (i ? ", " : "") + std::to_string(a.shape(i));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

Cloud cloudFromArrays(const py::handle& points, const py::object& amplitude, const py::object& confidence,
                      const char* function) {
  const FloatArray p = FloatArray::ensure(points);  // empty when not convertible to numbers
  if (!p) throw py::type_error(std::string(function) + ": expected a file path, a keyturn.Cloud or an array of points");
  const bool organized = p.ndim() == 3 && p.shape(2) == 3;
  if (!organized && !(p.ndim() == 2 && p.shape(1) == 3))
    throw py::value_error(std::string(function) + ": points must be an N × 3 or H × W × 3 array, not shape " +
                          shapeText(p));
  Cloud c;
  c.height = organized ? static_cast<std::uint32_t>(p.shape(0)) : 1;
  c.width = static_cast<std::uint32_t>(organized ? p.shape(1) : p.shape(0));
  const std::size_t n = static_cast<std::size_t>(c.width) * c.height;
  const float* in = p.data();
  c.points.resize(n);
  for (std::size_t i = 0; i < n; ++i) c.points[i] = Eigen::Vector3f(in[3 * i], in[3 * i + 1], in[3 * i + 2]);
  const auto channel = [&](const py::object& o, const char* what, std::vector<float>& out) {
    if (o.is_none()) return;
    const FloatArray a = FloatArray::ensure(o);
    if (!a || static_cast<std::size_t>(a.size()) != n || a.ndim() != (organized ? 2 : 1))
      throw py::value_error(std::string(function) + ": " + what + " must have one value per point (shape " +
                            (organized ? "H × W" : "N") + " as the points)");
    out.assign(a.data(), a.data() + n);
  };
  channel(amplitude, "amplitude", c.amplitude);
  channel(confidence, "confidence", c.confidence);
  return c;
}

bool isPath(const py::handle& h) {
  return py::isinstance<py::str>(h) || py::hasattr(h, "__fspath__");
}

Cloud loadUnlocked(const std::string& path) {
  py::gil_scoped_release release;
  return loadCloud(path);
}

}  // namespace

Error namedError(const std::string& name, const Error& e) {
  const std::string msg = e.what();
  return Error(msg.rfind(name, 0) == 0 ? msg : name + ": " + msg);
}

Cloud cloudFrom(const py::handle& source, const char* function, std::string* name) {
  if (isPath(source)) {
    const std::string path = py::str(py::module_::import("os").attr("fspath")(source));
    *name = path;
    return loadUnlocked(path);
  }
  *name = "points";
  if (py::isinstance<Cloud>(source)) return source.cast<Cloud>();
  return cloudFromArrays(source, py::none(), py::none(), function);
}

void bindClouds(py::module_& m) {
  py::class_<Cloud>(m, "Cloud", "A point cloud: points in metres (camera frame), amplitude and confidence when present")
      .def(py::init([](const py::object& points, const py::object& amplitude, const py::object& confidence) {
             return cloudFromArrays(points, amplitude, confidence, "Cloud");
           }),
           py::arg("points"), py::arg("amplitude") = py::none(), py::arg("confidence") = py::none(),
           "From an N × 3 (or organized H × W × 3, NaN for no point) array, amplitude and confidence of the same layout")
      .def_property_readonly("points", &pointsArray, "float32, N × 3 or H × W × 3 (NaN where a pixel has no point)")
      .def_property_readonly("amplitude", [](const Cloud& c) { return channelArray(c, c.amplitude); },
                             "float32, N or H × W; None when the file has none")
      .def_property_readonly("confidence", [](const Cloud& c) { return channelArray(c, c.confidence); },
                             "float32, N or H × W; None when the file has none")
      .def_property_readonly("organized", &Cloud::organized)
      .def_readonly("width", &Cloud::width)
      .def_readonly("height", &Cloud::height)
      .def_property_readonly("valid_count", &Cloud::validCount, "points with finite coordinates")
      .def("__len__", &Cloud::size)
      .def("__repr__", [](const Cloud& c) {
        return "<keyturn.Cloud " + std::to_string(c.width) + " × " + std::to_string(c.height) + ", " +
               std::to_string(c.validCount()) + " valid points>";
      });
  m.def(
      "load_cloud",
      [](const py::object& path) {
        if (!isPath(path)) throw py::type_error("load_cloud: expected a file path (str or os.PathLike)");
        return loadUnlocked(py::str(py::module_::import("os").attr("fspath")(path)));
      },
      py::arg("path"),
      "Reads a PCD or PLY file as keyturn reads it: a keyturn.Cloud (.points, .amplitude, .confidence as numpy "
      "arrays). Raises keyturn.Error naming the file when it cannot be read.");
}

}  // namespace keyturn::python
