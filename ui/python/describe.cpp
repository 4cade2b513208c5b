// keyturn.describe: one view through the whole chain (filter → working resolution →
// ISS → keypoint and shape functions → PDFs), the numbers `keyturn describe` writes.
#include <pybind11/stl.h>

#include "bindings.h"
#include "keyturn/core/features.h"
#include "keyturn/core/view_explanation.h"

namespace keyturn::python {
namespace {

struct Description {
  ViewDescriptor d;
  PointSet points;          // the points described; keypoint indices point into them
  py::object explanation;   // str with explain=True, else None
};

py::array_t<float> xyz(const std::vector<Eigen::Vector3f>& v) {
  py::array_t<float> a({static_cast<py::ssize_t>(v.size()), static_cast<py::ssize_t>(3)});
  float* out = a.mutable_data();
  for (std::size_t i = 0; i < v.size(); ++i)
    for (int k = 0; k < 3; ++k) out[3 * i + static_cast<std::size_t>(k)] = v[i][k];
  return a;
}

py::array_t<double> doubles(const std::vector<double>& v) {
  py::array_t<double> a(static_cast<py::ssize_t>(v.size()));
  std::copy(v.begin(), v.end(), a.mutable_data());
  return a;
}

py::dict filterReport(const ViewDescriptor& d) {
  const FilterReport& f = d.filter;
  py::list steps;
  for (const auto& s : f.steps) {
    py::dict step;
    step["name"] = s.name;
    step["applied"] = s.applied;
    step["before"] = s.before;
    step["after"] = s.after;
    step["removed"] = s.removed();
    step["flagged"] = s.flagged;
    step["note"] = s.note;
    steps.append(step);
  }
  py::dict r;
  // As describe's CSV: "unfiltered" when the filter was off.
  r["input_kind"] = f.steps.empty() ? "unfiltered" : inputKindName(f.kind);
  r["steps"] = steps;
  r["plane_found"] = f.plane_found;
  r["plane"] = std::vector<float>(f.plane.data(), f.plane.data() + 4);
  r["flagged"] = f.flaggedSummary();
  return r;
}

py::dict workingReport(const ViewDescriptor& d) {
  py::dict r;
  r["spacing_m"] = d.working.spacing;
  r["extent_m"] = d.working.extent;
  r["subsampled"] = d.working.subsampled;
  r["before"] = d.working.before;
  r["after"] = d.working.after;
  r["removed"] = d.working.before - d.working.after;
  return r;
}

Description describeSource(const py::object& source, const py::object& features, bool explain,
                           const std::string& kind, const py::object& shape, const py::kwargs& kwargs) {
  DescriptorOptions o = optionsFrom(kwargs, "describe");
  if (!features.is_none()) {
    std::string list;
    if (py::isinstance<py::str>(features)) list = features.cast<std::string>();
    else
      for (const auto& f : features) list += (list.empty() ? "" : ",") + std::string(py::str(f));
    try {
      o.features = parseFeatureList(list);
    } catch (const Error& e) {
      throw py::value_error(std::string("describe: features: ") + e.what());
    }
  }
  std::string name;
  const Cloud cloud = cloudFrom(source, "describe", &name, inputForm(kind, shape, "describe"));
  Description r;
  try {
    py::gil_scoped_release release;
    r.d = describeView(cloud, o, &r.points);
  } catch (const Error& e) {
    throw namedError(name, e);
  }
  r.explanation = py::none();
  if (explain) {
    const std::string text = explainView(name, r.d);
    py::module_::import("sys").attr("stderr").attr("write")(text);
    r.explanation = py::str(text);
  }
  return r;
}

}  // namespace

void bindDescribe(py::module_& m) {
  py::class_<Description>(m, "Description", "One view described: the numbers of its `keyturn describe` CSV row and more")
      .def_property_readonly("features", [](const Description& r) {
        std::vector<std::string> n;
        for (Feature f : r.d.features) n.push_back(featureName(f));
        return n;
      }, "feature names, in the order of the feature vector")
      .def_property_readonly("pdfs", [](const Description& r) {
        py::dict d;
        for (std::size_t i = 0; i < r.d.features.size(); ++i) d[py::str(featureName(r.d.features[i]))] = doubles(r.d.pdfs[i]);
        return d;
      }, "feature name → its PDF (float64, one value per bin)")
      .def_property_readonly("feature_vector", [](const Description& r) { return doubles(r.d.featureVector()); },
                             "the PDFs concatenated (the CSV row's bins)")
      .def_property_readonly("K", [](const Description& r) { return r.d.keypointCount(); }, "ISS keypoints")
      .def_property_readonly("keypoints", [](const Description& r) { return xyz(r.d.keypoints); },
                             "keypoint positions, K × 3 (metres)")
      .def_property_readonly("keypoint_indices", [](const Description& r) {
        py::array_t<int> a(static_cast<py::ssize_t>(r.d.keypoint_index.size()));
        std::copy(r.d.keypoint_index.begin(), r.d.keypoint_index.end(), a.mutable_data());
        return a;
      }, "the keypoints as row indices into described_points")
      .def_property_readonly("described_points", [](const Description& r) { return xyz(r.points.points); },
                             "the points the chain described (filtered, at the working resolution), N × 3")
      .def_property_readonly("points", [](const Description& r) { return r.d.points; },
                             "how many points were described (the CSV's points)")
      .def_property_readonly("input_points", [](const Description& r) { return r.d.input_points; },
                             "valid points of the input")
      .def_property_readonly("resolution", [](const Description& r) { return r.d.resolution; },
                             "the cloud resolution the radii are multiples of (metres)")
      .def_property_readonly("low_keypoints", [](const Description& r) { return r.d.low_keypoints; },
                             "fewer keypoints than low_keypoints: the histograms are thin")
      .def_property_readonly("unreachable_keypoints", [](const Description& r) { return r.d.unreachable_keypoints; })
      .def_property_readonly("unreachable_pairs", [](const Description& r) { return r.d.unreachable_pairs; })
      .def_property_readonly("filter", [](const Description& r) { return filterReport(r.d); },
                             "the filter report: input_kind, steps (name, applied, before, after, removed, flagged, "
                             "note), plane_found, plane, flagged")
      .def_property_readonly("working", [](const Description& r) { return workingReport(r.d); },
                             "the working resolution: spacing_m, extent_m, subsampled, before, after, removed")
      .def_property_readonly("times_ms", [](const Description& r) {
        const StageTimes& t = r.d.times;
        py::dict d;
        d["filter"] = t.filter; d["resolution"] = t.resolution; d["iss"] = t.iss; d["kpd"] = t.kpd;
        d["graph"] = t.graph; d["geodesic"] = t.geodesic; d["osada"] = t.osada; d["histogram"] = t.histogram;
        d["total"] = t.total;
        return d;
      }, "milliseconds per stage")
      .def_readonly("explanation", &Description::explanation, "with explain=True: what --explain prints")
      .def("__repr__", [](const Description& r) {
        return "<keyturn.Description K=" + std::to_string(r.d.keypointCount()) + ", " + std::to_string(r.d.points) +
               " points, " + std::to_string(r.d.features.size()) + " features>";
      });

  const std::string doc =
      "describe(view, features=None, explain=False, *, kind='auto', shape=None, **parameters) -> Description\n\n"
      "Describes one view as `keyturn describe` does, with the same numbers. view: a PCD/PLY path, a keyturn.Cloud, "
      "an Open3D point cloud (o3d.geometry.PointCloud or o3d.t.geometry.PointCloud) or an N × 3 / H × W × 3 array "
      "(metres, NaN for no point). features: names or a comma-separated list "
      "(default: kpd2,kpd3,kpa3,gkpd1,gkpd2,gkpcd2; also d1–d4, a3). explain=True writes, and keeps in "
      ".explanation, what each filter step did. kind: 'auto' (H × W × 3 is a frame, N × 3 a segmented cloud; "
      "N × 3 points that look like a frame whose grid was lost warn with keyturn.OrganizedShapeLostWarning), "
      "'frame' (refused without its grid) or 'segmented' (described as one object, any grid dropped). "
      "shape=(H, W) puts N × 3 points back on their pixel grid (row-major). Releases the GIL while it computes. "
      "Raises FileNotFoundError for a missing file, keyturn.Error with keyturn's one-line message for a view it "
      "cannot describe.\n\n"
      "Parameters (keyword, the library's defaults; keyturn.parameters() lists them):\n" +
      parametersDoc();
  m.def("describe", &describeSource, py::arg("view"), py::arg("features") = py::none(), py::arg("explain") = false,
        py::kw_only(), py::arg("kind") = "auto", py::arg("shape") = py::none(), doc.c_str());
}

}  // namespace keyturn::python
