// keyturn.Dataset: a dataset's views with their labels and poses, and its feature
// cache (core/learning/feature_cache.h) read, or filled, as evaluate and train use it.
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <filesystem>

#include "bindings.h"
#include "keyturn/learning/feature_cache.h"
#include "keyturn/learning/feature_spec.h"
#include "keyturn/rig/dataset.h"
#include "keyturn/rig/dataset_views.h"
#include "keyturn/rig/sidecars.h"

namespace keyturn::python {
namespace {

namespace fs = std::filesystem;

struct View {
  learning::LabelledView labels;  // id, path, class, instance, elevation label
  rig::ViewRecord record;         // angles, capture time, files
  std::string root;
};

struct Features {
  std::vector<std::string> blocks;
  learning::FeatureTable table;
  std::string cache;
};

class PyDataset {
 public:
  explicit PyDataset(std::string root) : root_(std::move(root)) {
    py::gil_scoped_release release;
    views_ = rig::datasetViews(root_, &skipped_, &records_);
  }

  const std::string& root() const { return root_; }
  std::size_t size() const { return views_.size(); }
  View view(std::size_t i) const { return {views_.at(i), records_.at(i), root_}; }
  const std::vector<std::string>& skipped() const { return skipped_; }

  Features features(const py::object& blocks, int jobs, const py::kwargs& kwargs) const {
    Features f;
    if (py::isinstance<py::str>(blocks)) f.blocks = learning::featureSetBlocks(blocks.cast<std::string>());
    else
      for (const auto& b : blocks) f.blocks.push_back(py::str(b));
    const DescriptorOptions options = optionsFrom(kwargs, "Dataset.features");
    learning::featureLayout(learning::cacheBlocks(), options).select(f.blocks, {});  // a block the cache lacks, first
    {
      py::gil_scoped_release release;
      f.table = learning::loadOrDescribeCache({root_, views_, options, jobs, nullptr});
      f.cache = learning::featureCachePath(root_, options);
    }
    return f;
  }

 private:
  std::string root_;
  std::vector<learning::LabelledView> views_;
  std::vector<rig::ViewRecord> records_;
  std::vector<std::string> skipped_;
};

template <typename F>
py::list column(const learning::FeatureTable& t, F f) {
  py::list l;
  for (const auto& r : t.rows) l.append(f(r));
  return l;
}

}  // namespace

void bindDataset(py::module_& m) {
  py::class_<View>(m, "View", "One view of a dataset: its files, labels and pose")
      .def_property_readonly("id", [](const View& v) { return v.labels.id; }, "CLASS/INSTANCE/eLABEL/aANGLE")
      .def_property_readonly("path", [](const View& v) { return v.labels.path; }, "the point cloud (PCD)")
      .def_property_readonly("cls", [](const View& v) { return v.labels.cls; }, "class (category) label")
      .def_property_readonly("instance", [](const View& v) { return v.labels.instance; }, "instance label")
      .def_property_readonly("elevation", [](const View& v) { return v.labels.elevation; }, "elevation label")
      .def_property_readonly("elevation_deg", [](const View& v) { return v.record.elevation_deg; })
      .def_property_readonly("commanded_deg", [](const View& v) { return v.record.key.commanded_deg; },
                             "turntable angle asked for")
      .def_property_readonly("measured_deg", [](const View& v) { return v.record.measured_deg; },
                             "turntable angle read back")
      .def_property_readonly("captured_at", [](const View& v) { return v.record.captured_at; })
      .def_property_readonly(
          "camera_from_turntable",
          [](const View& v) -> py::object {
            const std::string sidecar = v.record.sidecar();
            if (sidecar.empty()) return py::none();
            const auto t = rig::readViewTransform((fs::path(v.root) / sidecar).string());
            if (!t) return py::none();
            return py::cast(*t);
          },
          "4 × 4 camera ← turntable transform from the view's sidecar; None when the rig was not calibrated")
      .def("__repr__", [](const View& v) { return "<keyturn.View " + v.labels.id + ">"; });

  py::class_<Features>(m, "Features", "A dataset's feature cache: rows of views, columns of the chosen blocks")
      .def_property_readonly("x", [](const Features& f) {
        std::vector<std::size_t> all(f.table.rows.size());
        for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
        const learning::Matrix x = f.table.select(f.blocks, all);
        py::array_t<float> a({static_cast<py::ssize_t>(x.rows()), static_cast<py::ssize_t>(x.cols())});
        std::copy(x.data(), x.data() + x.size(), a.mutable_data());
        return a;
      }, "float32, views × columns (the blocks concatenated); NaN where a view lacks a block")
      .def_property_readonly("blocks", [](const Features& f) { return f.blocks; })
      .def_property_readonly("ids", [](const Features& f) { return column(f.table, [](const auto& r) { return r.id; }); })
      .def_property_readonly("cls", [](const Features& f) { return column(f.table, [](const auto& r) { return r.cls; }); },
                             "class labels, one per row")
      .def_property_readonly("instance", [](const Features& f) {
        return column(f.table, [](const auto& r) { return r.instance; });
      }, "instance labels, one per row")
      .def_property_readonly("elevation", [](const Features& f) {
        return column(f.table, [](const auto& r) { return r.elevation; });
      })
      .def_property_readonly("keypoints", [](const Features& f) {
        return column(f.table, [](const auto& r) { return r.keypoints; });
      }, "K per view (-1: not described)")
      .def_property_readonly("problems", [](const Features& f) {
        return column(f.table, [](const auto& r) { return r.problem; });
      }, "why a view lacks a block ('' when it lacks none)")
      .def_property_readonly("spec", [](const Features& f) { return f.table.spec; },
                             "the feature specification the cache was made with")
      .def_readonly("cache", &Features::cache, "the cache file (DATASET/.keyturn/features-HASH.csv)")
      .def("__len__", [](const Features& f) { return f.table.rows.size(); });

  py::class_<PyDataset>(m, "Dataset", "A keyturn dataset folder (docs/dataset-format.md)")
      .def(py::init([](const py::object& path) {
             return PyDataset(py::str(py::module_::import("os").attr("fspath")(path)));
           }),
           py::arg("path"), "Reads the manifest; raises keyturn.Error for a folder that is not a dataset")
      .def_property_readonly("root", &PyDataset::root)
      .def_property_readonly("views", [](const PyDataset& d) {
        py::list l;
        for (std::size_t i = 0; i < d.size(); ++i) l.append(d.view(i));
        return l;
      }, "the views, manifest order")
      .def_property_readonly("skipped_rows", &PyDataset::skipped, "malformed manifest rows that were skipped")
      .def("__len__", &PyDataset::size)
      .def("__getitem__", [](const PyDataset& d, std::size_t i) {
        if (i >= d.size()) throw py::index_error("Dataset: view " + std::to_string(i) + " of " + std::to_string(d.size()));
        return d.view(i);
      })
      .def("features", &PyDataset::features, py::arg("blocks") = "kpd2+gkpd2", py::arg("jobs") = 0,
           ("features(blocks='kpd2+gkpd2', jobs=0, **parameters) -> Features\n\n"
            "The dataset's feature cache for these parameters (keyturn.parameters(); the library's defaults), as "
            "evaluate and train read it: read when present, else described (all cores, GIL released) and written. "
            "blocks: 'kpd2+gkpd2' or a list; any cache block: kpd2 … gkpcd2, d2, d3, a3, u_kpd2 … (random keypoints), "
            "s_kpd2 … s_d3 (lengths in RMS radii), size, esf, vfh, ourcvfh.\n\nParameters:\n" +
            parametersDoc())
               .c_str())
      .def("__repr__", [](const PyDataset& d) {
        return "<keyturn.Dataset " + d.root() + ", " + std::to_string(d.size()) + " views>";
      });
}

}  // namespace keyturn::python
