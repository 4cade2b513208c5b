// keyturn.Dataset: a dataset's views with their labels and poses (core/dataset), and its feature
// cache read, or filled, as evaluate and train use it (learning::datasetFeatures).
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <filesystem>
#include <optional>

#include "bindings.h"
#include "keyturn/dataset/dataset.h"
#include "keyturn/dataset/dataset_views.h"
#include "keyturn/dataset/sidecars.h"
#include "keyturn/learning/dataset_features.h"
#include "keyturn/learning/feature_spec.h"
#include "keyturn/learning/model_training.h"

namespace keyturn::python {
namespace {

namespace fs = std::filesystem;

struct View {
  dataset::LabelledView labels;  // id, path, class, instance, elevation label
  dataset::ViewRecord record;     // angles, capture time, files
  std::string root;
};

struct Features {
  std::vector<std::string> blocks;
  learning::FeatureTable table;
  std::optional<std::string> cache;  // the cache file read or written; none when described in memory
};

class PyDataset {
 public:
  explicit PyDataset(std::string root) : root_(std::move(root)) {
    requireFile(root_);
    py::gil_scoped_release release;
    views_ = dataset::datasetViews(root_, &skipped_, &records_);
  }

  const std::string& root() const { return root_; }
  std::size_t size() const { return views_.size(); }
  View view(std::size_t i) const { return {views_.at(i), records_.at(i), root_}; }
  const std::vector<std::string>& skipped() const { return skipped_; }

  // Reads the cache when it holds every view; else describes in memory. Writes the cache only
  // when asked (cache=True): a read has no side effect on the dataset.
  Features features(const py::object& blocks, int jobs, bool cache, const py::kwargs& kwargs) const {
    Features f;
    const DescriptorOptions options = optionsFrom(kwargs, "Dataset.features");
    const learning::FeatureTable full = learning::featureLayout(learning::cacheBlocks(), options);
    try {
      if (py::isinstance<py::str>(blocks)) f.blocks = learning::featureSetBlocks(blocks.cast<std::string>());
      else
        for (const auto& b : blocks) f.blocks.push_back(py::str(b));
      full.select(f.blocks, {});  // a block the cache lacks, first
    } catch (const Error& e) {
      throw py::value_error(std::string("Dataset.features: ") + e.what());
    }
    py::gil_scoped_release release;
    auto got = learning::datasetFeatures({root_, views_, options, jobs, nullptr},
                                         cache ? learning::CacheWrite::Fill : learning::CacheWrite::Never, f.blocks);
    f.table = std::move(got.table);
    if (!got.cache.empty()) f.cache = got.cache;
    return f;
  }

 private:
  std::string root_;
  std::vector<dataset::LabelledView> views_;
  std::vector<dataset::ViewRecord> records_;
  std::vector<std::string> skipped_;
};

template <typename F>
py::list column(const learning::FeatureTable& t, F f) {
  py::list l;
  for (const auto& r : t.rows) l.append(f(r));
  return l;
}

std::vector<std::string> blockList(const py::object& blocks) {
  std::vector<std::string> out;
  if (py::isinstance<py::str>(blocks)) return learning::featureSetBlocks(blocks.cast<std::string>());
  for (const auto& b : blocks) out.push_back(py::str(b));
  return out;
}

// Views described one by one into a table of these blocks, labelled: what Dataset.features gives
// for a dataset, for views from anywhere (files, clouds, Open3D, arrays).
Features featuresOf(const py::sequence& views, const py::sequence& labels, const py::object& blocks,
                    const py::object& ids, const std::string& kind, const py::kwargs& kwargs) {
  const DescriptorOptions options = optionsFrom(kwargs, "features_of");
  if (views.size() != labels.size())
    throw py::value_error("features_of: " + std::to_string(views.size()) + " views but " +
                          std::to_string(labels.size()) + " labels");
  if (!ids.is_none() && py::len(ids) != views.size())
    throw py::value_error("features_of: ids must have one entry per view");
  Features f;
  try {
    f.blocks = blockList(blocks);
    std::vector<std::string> unique;
    for (const auto& b : f.blocks)
      if (std::find(unique.begin(), unique.end(), b) == unique.end()) unique.push_back(b);
    f.table = learning::featureLayout(unique, options);
  } catch (const Error& e) {
    throw py::value_error(std::string("features_of: ") + e.what());
  }
  const InputForm form = inputForm(kind, py::none(), "features_of");
  for (std::size_t i = 0; i < views.size(); ++i) {
    std::string name;
    const Cloud cloud = cloudFrom(views[i], "features_of", &name, form);
    learning::FeatureRow row;
    {
      py::gil_scoped_release release;
      row = learning::describeCloud(cloud, options, f.table);
    }
    row.id = ids.is_none() ? (name == "points" ? "view" + std::to_string(i) : name) : std::string(py::str(ids[py::int_(i)]));
    row.cls = row.instance = py::str(labels[i]);
    f.table.rows.push_back(std::move(row));
  }
  return f;
}

py::object train(const Features& f, const py::object& blocks, const py::object& rows, const std::string& classifier,
                 const std::string& label, std::uint64_t seed, const py::object& rounds, const py::object& epochs,
                 const std::string& open_set, double false_accept, int open_set_groups,
                 const std::string& open_set_rule) {
  learning::ClassifierParams params;
  params.kind = classifier;
  params.seed = seed;
  if (classifier != "xgboost" && classifier != "mlp" && classifier != "setnet")
    throw py::value_error("train: classifier must be 'xgboost', 'mlp' or 'setnet', not '" + classifier + "'");
  if (!rounds.is_none()) params.xgboost.rounds = rounds.cast<int>();
  if (!epochs.is_none()) params.mlp.epochs = params.setnet.epochs = epochs.cast<int>();
  if (params.xgboost.rounds < 1 || params.mlp.epochs < 1) throw py::value_error("train: rounds and epochs must be >= 1");
  learning::LabelKind kind = learning::LabelKind::Instance;
  std::vector<std::string> use = f.blocks;
  learning::OpenSetOptions open;
  open.false_accept = false_accept;
  if (!(false_accept >= 0 && false_accept < 1)) throw py::value_error("train: false_accept must be within [0, 1)");
  // The CLI's bounds (--open-set-groups 2..1000).
  if (open_set_groups < 2 || open_set_groups > 1000)
    throw py::value_error("train: open_set_groups must be within 2..1000, not " + std::to_string(open_set_groups));
  open.groups = open_set_groups;
  open.rule = open_set_rule;
  try {
    learning::checkOpenSetRule(open_set_rule);
    learning::setOpenSetMethod(open, open_set);
    kind = learning::parseLabelKind(label);
    if (!blocks.is_none()) {
      use.clear();
      use = blockList(blocks);
      f.table.select(use, {});
    }
  } catch (const Error& e) {
    throw py::value_error(std::string("train: ") + e.what());
  }
  learning::FeatureTable table = f.table;
  if (!rows.is_none()) {
    py::array picked = py::module_::import("numpy").attr("asarray")(rows);
    if (picked.dtype().kind() == 'b') {
      if (static_cast<std::size_t>(picked.size()) != f.table.rows.size())
        throw py::value_error("train: a boolean rows mask needs one value per view (" +
                              std::to_string(f.table.rows.size()) + ")");
      picked = py::module_::import("numpy").attr("flatnonzero")(picked);
    }
    table.rows.clear();
    const auto n = static_cast<long long>(f.table.rows.size());
    for (const auto& r : picked.attr("tolist")().cast<std::vector<long long>>()) {
      if (r < -n || r >= n) throw py::index_error("train: row " + std::to_string(r) + " of " + std::to_string(n));
      table.rows.push_back(f.table.rows[static_cast<std::size_t>(r < 0 ? r + n : r)]);
    }
  }
  if (table.rows.empty()) throw py::value_error("train: no views to train on");
  learning::Model model;
  try {
    py::gil_scoped_release release;
    model = learning::trainModel(table, use, kind, params, nullptr, open);
  } catch (const Error& e) {
    throw py::value_error(std::string("train: ") + e.what());
  }
  return wrapModel(std::move(model), "<model trained on " + std::to_string(table.rows.size()) + " views>");
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
            const auto t = dataset::readViewTransform((fs::path(v.root) / sidecar).string());
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
      .def_readonly("cache", &Features::cache,
                    "the cache file read or written (DATASET/.keyturn/features-HASH.csv); None when described in memory")
      .def("__len__", [](const Features& f) { return f.table.rows.size(); });

  m.def("features_of", &featuresOf, py::arg("views"), py::arg("labels"), py::arg("blocks") = "kpa3+s_kpd2",
        py::kw_only(), py::arg("ids") = py::none(), py::arg("kind") = "auto",
        "features_of(views, labels, blocks='kpa3+s_kpd2', *, ids=None, kind='auto', **parameters) -> Features\n\n"
        "Views from anywhere (paths, keyturn.Cloud, Open3D clouds, arrays) described one by one into Features, each "
        "row labelled (cls and instance) with its label: what Dataset.features gives for a dataset, for keyturn.train. "
        "ids name the rows (default: the file, or viewI). kind as for describe.");
  m.def("train", &train, py::arg("features"), py::arg("blocks") = py::none(), py::kw_only(),
        py::arg("rows") = py::none(), py::arg("classifier") = "xgboost", py::arg("label") = "instance", py::arg("seed") = 7,
        py::arg("rounds") = py::none(), py::arg("epochs") = py::none(), py::arg("open_set") = "none",
        py::arg("false_accept") = 0.05, py::arg("open_set_groups") = 5, py::arg("open_set_rule") = "pooled",
        "train(features, blocks=None, *, rows=None, classifier='xgboost', label='instance', seed=7, rounds=None, "
        "epochs=None, open_set='none', false_accept=0.05, open_set_groups=5, open_set_rule='pooled') -> Model\n\n"
        "A classifier trained on a dataset's features (Dataset.features, features_of), as `keyturn train` trains "
        "it: on the features' blocks (or `blocks`), on every view or those of rows (indices or a boolean mask), labelled by instance or category (the class column), XGBoost (rounds, "
        "default 30), the libtorch network (epochs, default 30) or, classifier='setnet', the set network over the "
        "keypoints (blocks 'kpset' first; epochs, default 30). Model.save writes it; Model.classify applies it "
        "with the features' parameters. open_set: 'none' (closed-set, the default), 'knn-relative', 'knn' or "
        "'max-probability' (a threshold calibrated for false_accept on categories left out in turn; needs at least 3 "
        "categories) or 'auto' (knn-relative where the views have 3 categories, else closed-set) (Model.open_set); "
        "open_set_groups: the groups of categories left out in turn (trainings; 2..1000), open_set_rule: the rate "
        "met on their views pooled or on each group's alone ('per-group'), as train's --open-set-groups and "
        "--open-set-rule. GIL released while it trains.");

  py::class_<PyDataset>(m, "Dataset", "A keyturn dataset folder (docs/dataset-format.md)")
      .def(py::init([](const py::object& path) {
             return PyDataset(py::str(py::module_::import("os").attr("fspath")(path)));
           }),
           py::arg("path"),
           "Reads the manifest; raises FileNotFoundError for a missing folder, keyturn.Error for a folder that is not "
           "a dataset")
      .def_property_readonly("root", &PyDataset::root)
      .def_property_readonly("views", [](const PyDataset& d) {
        py::list l;
        for (std::size_t i = 0; i < d.size(); ++i) l.append(d.view(i));
        return l;
      }, "the views, manifest order")
      .def_property_readonly("skipped_rows", &PyDataset::skipped, "malformed manifest rows that were skipped")
      .def("__len__", &PyDataset::size)
      .def("__getitem__", [](const PyDataset& d, long long i) {
        const auto n = static_cast<long long>(d.size());
        if (i < -n || i >= n)
          throw py::index_error("Dataset: view " + std::to_string(i) + " of " + std::to_string(n));
        return d.view(static_cast<std::size_t>(i < 0 ? i + n : i));
      })
      .def("__iter__", [](const PyDataset& d) {
        py::list l;
        for (std::size_t i = 0; i < d.size(); ++i) l.append(d.view(i));
        return py::iter(l);
      })
      .def("features", &PyDataset::features, py::arg("blocks") = "kpa3+s_kpd2", py::arg("jobs") = 0, py::kw_only(),
           py::arg("cache") = false,
           ("features(blocks='kpa3+s_kpd2', jobs=0, *, cache=False, **parameters) -> Features\n\n"
            "The dataset's features for these parameters (keyturn.parameters(); the library's defaults), as "
            "evaluate and train compute them: read from the dataset's feature cache when it holds every view, else "
            "described in memory (all cores, GIL released) and nothing written. cache=True fills the cache "
            "(DATASET/.keyturn/features-HASH.csv, as `keyturn describe DATASET --cache`) when it lacks views. "
            "blocks: 'kpa3+s_kpd2' or a list; any cache block: kpd2 … gkpcd2, their scaled twins s_kpd2 …, d2, d3, a3, u_kpd2 … (random keypoints), "
            "s_kpd2 … s_d3 (lengths in RMS radii), size, esf, vfh, ourcvfh.\n\nParameters:\n" +
            parametersDoc())
               .c_str())
      .def("__repr__", [](const PyDataset& d) {
        return "<keyturn.Dataset " + d.root() + ", " + std::to_string(d.size()) + " views>";
      });
}

}  // namespace keyturn::python
