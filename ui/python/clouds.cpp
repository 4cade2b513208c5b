// keyturn.Cloud, load_cloud, save_cloud and from_open3d: point clouds between keyturn, numpy and
// Open3D. N × 3 or, organized, H × W × 3 with NaN where a pixel has no point; amplitude and
// confidence alongside. A Cloud exposes its points through the buffer protocol.
#include <pybind11/stl.h>

#include <cerrno>
#include <cmath>
#include <filesystem>

#include "bindings.h"
#include "keyturn/core/camera_file.h"
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
  if (!p) {
    PyErr_Clear();
    throw py::type_error(std::string(function) +
                         ": expected a file path, a keyturn.Cloud, an Open3D point cloud or an array of points, not " +
                         std::string(py::str(py::type::of(points).attr("__name__"))));
  }
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
    if (!a) PyErr_Clear();
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

std::string pathText(const py::handle& h) {
  return py::str(py::module_::import("os").attr("fspath")(h));
}

bool isOpen3d(const py::handle& h) {
  const std::string module = py::str(py::type::of(h).attr("__module__"));
  return module.rfind("open3d", 0) == 0;
}

// An Open3D tensor attribute ("positions", "amplitude") as a numpy array on the CPU; None when absent.
py::object tensorAttribute(const py::handle& cloud, const char* name) {
  const py::object map = cloud.attr("point");
  if (!map.contains(name)) return py::none();
  return map[name].attr("cpu")().attr("numpy")();
}

// An Open3D cloud (legacy o3d.geometry.PointCloud or tensor o3d.t.geometry.PointCloud) as a Cloud:
// its points N × 3 (Open3D keeps no pixel grid); a tensor cloud's amplitude and confidence
// attributes (N or N × 1) come along.
Cloud cloudFromOpen3d(const py::handle& o, const char* function) {
  const py::module_ np = py::module_::import("numpy");
  if (py::hasattr(o, "point")) {
    const py::object positions = tensorAttribute(o, "positions");
    if (positions.is_none())
      throw py::value_error(std::string(function) + ": the Open3D tensor point cloud has no positions");
    const auto flat = [&](const py::object& a) -> py::object {
      return a.is_none() ? a : np.attr("reshape")(a, -1);
    };
    return cloudFromArrays(positions, flat(tensorAttribute(o, "amplitude")), flat(tensorAttribute(o, "confidence")),
                           function);
  }
  if (py::hasattr(o, "points")) return cloudFromArrays(np.attr("asarray")(o.attr("points")), py::none(), py::none(), function);
  throw py::type_error(std::string(function) + ": an Open3D " +
                       std::string(py::str(py::type::of(o).attr("__name__"))) + " is not a point cloud");
}

Cloud loadUnlocked(const std::string& path, const DepthImageOptions& depth = {}) {
  requireFile(path);
  py::gil_scoped_release release;
  return loadCloud(path, depth);
}

// Unorganized points that look like a frame whose pixel grid was lost: NaN rows (a grid keeps its
// holes, a segmented object has none) or a scene far wider than an object. Empty when they do not.
constexpr float kSceneSpanM = 1.5f;  // wider than any object keyturn describes on its own

std::string lostGridSign(const Cloud& c) {
  std::size_t invalid = 0, zero = 0;
  Eigen::Vector3f lo = Eigen::Vector3f::Constant(INFINITY), hi = Eigen::Vector3f::Constant(-INFINITY);
  for (const auto& p : c.points) {
    if (!Cloud::isValid(p)) {
      ++invalid;
      continue;
    }
    if (p.isZero()) ++zero;
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  if (invalid > 0) return std::to_string(invalid) + " of them NaN";
  if (zero > 1) return std::to_string(zero) + " of them at (0, 0, 0), the no-return of a depth image";
  const float span = (hi - lo).norm();
  if (std::isfinite(span) && span > kSceneSpanM) {
    char b[32];
    std::snprintf(b, sizeof b, "%.1f", span);
    return std::string("spanning ") + b + " m, a scene rather than an object";
  }
  return {};
}

}  // namespace

// The warning's class, made once at import and kept for the process (never released: a static
// py::object would be released after the interpreter is gone).
static PyObject* organizedShapeLostWarning = nullptr;

void requireFile(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) {
    PyErr_SetObject(PyExc_FileNotFoundError,
                    py::make_tuple(ENOENT, "No such file or directory", path).ptr());
    throw py::error_already_set();
  }
}

Error namedError(const std::string& name, const Error& e) {
  const std::string msg = e.what();
  return Error(msg.rfind(name, 0) == 0 ? msg : name + ": " + msg);
}

InputForm inputForm(const std::string& kind, const py::object& shape, const char* function) {
  InputForm f;
  if (kind == "auto") f.kind = InputForm::Auto;
  else if (kind == "frame") f.kind = InputForm::Frame;
  else if (kind == "segmented") f.kind = InputForm::Segmented;
  else
    throw py::value_error(std::string(function) + ": kind must be 'auto', 'frame' or 'segmented', not '" + kind + "'");
  if (!shape.is_none()) {
    std::vector<long long> hw;
    try {
      hw = shape.cast<std::vector<long long>>();
    } catch (const py::cast_error&) {
      throw py::type_error(std::string(function) + ": shape must be (H, W), two ints");
    }
    if (hw.size() != 2 || hw[0] < 1 || hw[1] < 1)
      throw py::value_error(std::string(function) + ": shape must be (H, W), two positive ints");
    f.height = static_cast<std::uint32_t>(hw[0]);
    f.width = static_cast<std::uint32_t>(hw[1]);
  }
  return f;
}

Cloud cloudFrom(const py::handle& source, const char* function, std::string* name, const InputForm& form) {
  Cloud c;
  bool from_file = false;
  if (isPath(source)) {
    *name = pathText(source);
    c = loadUnlocked(*name);
    from_file = true;
  } else {
    *name = "points";
    if (py::isinstance<Cloud>(source)) c = source.cast<Cloud>();
    else if (isOpen3d(source)) c = cloudFromOpen3d(source, function);
    else c = cloudFromArrays(source, py::none(), py::none(), function);
  }
  if (form.width) {
    const std::size_t n = static_cast<std::size_t>(form.width) * form.height;
    if (c.organized() ? (c.width != form.width || c.height != form.height) : c.size() != n)
      throw py::value_error(std::string(function) + ": shape (" + std::to_string(form.height) + ", " +
                            std::to_string(form.width) + ") needs " + std::to_string(n) + " points, not " +
                            std::to_string(c.size()) + (c.organized() ? " in another grid" : ""));
    c.width = form.width;
    c.height = form.height;  // rows in row-major pixel order, as Open3D keeps an organized PCD's points
  }
  switch (form.kind) {
    case InputForm::Frame:
      if (!c.organized())
        throw py::value_error(std::string(function) + ": kind='frame' needs the pixel grid: an H × W × 3 array, or "
                              "shape=(H, W) for N × 3 points in row-major pixel order (" + *name + " has " +
                              std::to_string(c.size()) + " points without one)");
      break;
    case InputForm::Segmented:
      c.width = static_cast<std::uint32_t>(c.size());  // the grid dropped: one object, its points in any order
      c.height = 1;
      break;
    case InputForm::Auto:
      if (form.warn && !from_file && !c.organized()) {
        const std::string sign = lostGridSign(c);
        if (!sign.empty())
          py::module_::import("warnings")
              .attr("warn")(std::string(function) + ": " + std::to_string(c.size()) + " × 3 points, " + sign +
                                ": a frame whose pixel grid was lost (Open3D keeps none)? Described as a segmented "
                                "cloud; pass shape=(H, W) to describe the frame, or kind='segmented' to say it is one "
                                "object",
                            py::handle(organizedShapeLostWarning), 2);
      }
      break;
  }
  return c;
}

static DepthImageOptions depthOptions(const py::object& camera, const py::object& intrinsics, const py::object& depth_scale,
                               const char* function) {
  DepthImageOptions o;
  if (!camera.is_none() && !intrinsics.is_none())
    throw py::value_error(std::string(function) + ": camera and intrinsics: give one or the other");
  if (!camera.is_none()) {
    if (!isPath(camera)) throw py::type_error(std::string(function) + ": camera must be a camera file's path");
    const std::string path = pathText(camera);
    requireFile(path);
    o = readCameraFile(path);
  }
  if (!intrinsics.is_none()) {
    DepthIntrinsics k;
    if (py::hasattr(intrinsics, "intrinsic_matrix")) {  // o3d.camera.PinholeCameraIntrinsic
      const py::array_t<double> m = py::array_t<double, py::array::forcecast>::ensure(intrinsics.attr("intrinsic_matrix"));
      k = {m.at(0, 0), m.at(1, 1), m.at(0, 2), m.at(1, 2)};
    } else if (py::isinstance<py::dict>(intrinsics)) {
      const py::dict d = intrinsics.cast<py::dict>();
      for (const char* key : {"fx", "fy", "cx", "cy"})
        if (!d.contains(key))
          throw py::value_error(std::string(function) + ": intrinsics needs fx, fy, cx and cy (pixels); " + key +
                                " is missing");
      k = {d["fx"].cast<double>(), d["fy"].cast<double>(), d["cx"].cast<double>(), d["cy"].cast<double>()};
    } else {
      std::vector<double> v;
      try {
        v = intrinsics.cast<std::vector<double>>();
      } catch (const py::cast_error&) {
      }
      if (v.size() != 4)
        throw py::value_error(std::string(function) +
                              ": intrinsics must be (fx, fy, cx, cy), a dict of them or an "
                              "o3d.camera.PinholeCameraIntrinsic");
      k = {v[0], v[1], v[2], v[3]};
    }
    if (!(k.fx > 0) || !(k.fy > 0)) throw py::value_error(std::string(function) + ": fx and fy must be positive");
    o.intrinsics = k;
  }
  if (!depth_scale.is_none()) {
    const double s = depth_scale.cast<double>();
    if (!(s > 0)) throw py::value_error(std::string(function) + ": depth_scale must be positive (metres per unit)");
    o.depth_scale = s;
  }
  return o;
}

void bindClouds(py::module_& m) {
  organizedShapeLostWarning =
      PyErr_NewExceptionWithDoc("keyturn.OrganizedShapeLostWarning",
                                "An N × 3 array that looks like a frame whose pixel grid was lost", PyExc_UserWarning,
                                nullptr);
  if (!organizedShapeLostWarning) throw py::error_already_set();
  m.attr("OrganizedShapeLostWarning") = py::handle(organizedShapeLostWarning);

  py::class_<Cloud>(m, "Cloud", py::buffer_protocol(),
                    "A point cloud: points in metres (camera frame), amplitude and confidence when present. "
                    "np.asarray(cloud) is its points, N × 3 or H × W × 3 float32, without a copy (read-only).")
      .def(py::init([](const py::object& points, const py::object& amplitude, const py::object& confidence,
                       const py::object& shape) {
             if (isOpen3d(points)) {
               if (!amplitude.is_none() || !confidence.is_none())
                 throw py::value_error("Cloud: amplitude and confidence come from the Open3D cloud's attributes");
               std::string name;
               return cloudFrom(points, "Cloud", &name, inputForm("auto", shape, "Cloud"));
             }
             Cloud c = cloudFromArrays(points, amplitude, confidence, "Cloud");
             if (!shape.is_none()) {
               if (!amplitude.is_none() || !confidence.is_none())
                 throw py::value_error("Cloud: shape with amplitude or confidence: give them H × W × 3 and H × W");
               std::string name = "points";
               c = cloudFrom(py::cast(c), "Cloud", &name, inputForm("auto", shape, "Cloud"));
             }
             return c;
           }),
           py::arg("points"), py::arg("amplitude") = py::none(), py::arg("confidence") = py::none(),
           py::arg("shape") = py::none(),
           "From an N × 3 (or organized H × W × 3, NaN for no point) array, amplitude and confidence of the same "
           "layout; or from an Open3D point cloud. shape=(H, W) puts N × 3 points back on their pixel grid.")
      .def_buffer([](Cloud& c) -> py::buffer_info {
        static float none[3] = {0, 0, 0};
        float* data = c.points.empty() ? none : c.points.front().data();
        const auto f = static_cast<py::ssize_t>(sizeof(float));
        std::vector<py::ssize_t> shape = layoutShape(c, true), strides;
        if (c.organized()) strides = {3 * f * static_cast<py::ssize_t>(c.width), 3 * f, f};
        else strides = {3 * f, f};
        return py::buffer_info(data, f, py::format_descriptor<float>::format(), static_cast<py::ssize_t>(shape.size()),
                               shape, strides, true);
      })
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
      .def(py::pickle(
          [](const Cloud& c) {
            return py::make_tuple(pointsArray(c), channelArray(c, c.amplitude), channelArray(c, c.confidence));
          },
          [](const py::tuple& t) {
            if (t.size() != 3) throw py::value_error("Cloud: not a pickled keyturn.Cloud");
            return cloudFromArrays(t[0], t[1], t[2], "Cloud");
          }))
      .def("__repr__", [](const Cloud& c) {
        return "<keyturn.Cloud " + std::to_string(c.width) + " × " + std::to_string(c.height) + ", " +
               std::to_string(c.validCount()) + " valid points>";
      });
  m.def(
      "load_cloud",
      [](const py::object& path, const py::object& camera, const py::object& intrinsics, const py::object& depth_scale) {
        if (!isPath(path)) throw py::type_error("load_cloud: expected a file path (str or os.PathLike)");
        return loadUnlocked(pathText(path), depthOptions(camera, intrinsics, depth_scale, "load_cloud"));
      },
      py::arg("path"), py::kw_only(), py::arg("camera") = py::none(), py::arg("intrinsics") = py::none(),
      py::arg("depth_scale") = py::none(),
      "load_cloud(path, *, camera=None, intrinsics=None, depth_scale=None) -> Cloud\n\n"
      "Reads a PCD or PLY file as keyturn reads it, or a 16-bit depth PNG as an organized cloud: a keyturn.Cloud "
      "(.points, .amplitude, .confidence as numpy arrays). A depth PNG needs the camera: camera= a camera file "
      "as `keyturn describe --camera` reads (JSON or YAML: fx, fy, cx, cy in pixels, optional depth_scale), or "
      "intrinsics= (fx, fy, cx, cy), a dict of them or an o3d.camera.PinholeCameraIntrinsic; depth_scale in "
      "metres per unit (default 0.001). Raises FileNotFoundError for a missing file, keyturn.Error naming the "
      "file when it cannot be read.");
  m.def(
      "save_cloud",
      [](const py::object& path, const py::object& cloud, const std::string& encoding) {
        if (!isPath(path)) throw py::type_error("save_cloud: expected a file path (str or os.PathLike)");
        PcdEncoding e = PcdEncoding::BinaryCompressed;
        if (encoding == "ascii") e = PcdEncoding::Ascii;
        else if (encoding == "binary") e = PcdEncoding::Binary;
        else if (encoding != "binary_compressed")
          throw py::value_error("save_cloud: encoding must be 'binary_compressed', 'binary' or 'ascii', not '" +
                                encoding + "'");
        const std::string file = pathText(path);
        std::string ext = std::filesystem::path(file).extension().string();
        for (char& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
        if (ext != ".pcd" && ext != ".ply")
          throw py::value_error("save_cloud: " + file + ": the name must end in .pcd or .ply");
        std::string name;
        InputForm form;
        form.warn = false;
        const Cloud c = cloudFrom(cloud, "save_cloud", &name, form);
        py::gil_scoped_release release;
        saveCloud(file, c, e);
      },
      py::arg("path"), py::arg("cloud"), py::arg("encoding") = "binary_compressed",
      "save_cloud(path, cloud, encoding='binary_compressed')\n\n"
      "Writes a keyturn.Cloud, an N × 3 / H × W × 3 array or an Open3D point cloud as PCD (organized clouds stay "
      "organized; encoding 'binary_compressed', 'binary' or 'ascii') or PLY, by the name's extension: x, y, z and "
      "amplitude, confidence when present. load_cloud reads it back.");
  m.def(
      "from_open3d",
      [](const py::object& cloud, const py::object& shape) {
        if (!isOpen3d(cloud)) throw py::type_error("from_open3d: expected an Open3D point cloud");
        std::string name;
        return cloudFrom(cloud, "from_open3d", &name, inputForm("auto", shape, "from_open3d"));
      },
      py::arg("cloud"), py::arg("shape") = py::none(),
      "from_open3d(cloud, shape=None) -> Cloud\n\nAn o3d.geometry.PointCloud or o3d.t.geometry.PointCloud as a "
      "keyturn.Cloud (a tensor cloud's amplitude and confidence attributes too). shape=(H, W) puts the points "
      "back on their pixel grid (an organized PCD read with remove_nan_points=False).");
}

}  // namespace keyturn::python
