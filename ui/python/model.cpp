// keyturn.Model: a trained model (keyturn train) classifying views as `keyturn classify`
// does: described with the model's own parameters and only its blocks.
#include <pybind11/stl.h>

#include <cmath>
#include <mutex>
#include <optional>

#include "bindings.h"
#include "keyturn/learning/feature_cache.h"
#include "keyturn/learning/model_predictions.h"

namespace keyturn::python {
namespace {

struct Classification {
  std::string cls;                 // the answer: a class, "unknown" or "no object"
  double probability = 0;          // of the most probable class (0 for no object)
  std::vector<std::pair<std::string, double>> probabilities;  // the model's class order
  int keypoints = 0;
  std::string problem;
  std::string answer = "class";    // "class", "unknown" or "no object"
  std::string best;                // the most probable class ("" for no object)
  std::optional<double> score, threshold;  // the open-set test; None for a closed-set model
};

class PyModel {
 public:
  explicit PyModel(std::string dir) : source_(std::move(dir)) {
    requireFile(source_);
    py::gil_scoped_release release;
    model_ = learning::loadModel(source_);
    layout_ = learning::modelLayout(model_, source_);
    options_ = learning::modelOptions(model_, source_);
  }
  // A model just trained (keyturn.train); `source` names it in messages until it is saved.
  PyModel(learning::Model model, std::string source) : source_(std::move(source)), model_(std::move(model)) {
    layout_ = learning::modelLayout(model_, source_);
    options_ = learning::modelOptions(model_, source_);
  }

  void save(const std::string& dir) {
    {
      py::gil_scoped_release release;
      std::lock_guard<std::mutex> lock(predict_mutex_);
      learning::saveModel(dir, model_);
    }
    source_ = dir;
  }

  Classification classify(const py::object& view, const std::string& kind, const py::object& shape) {
    std::string name;
    const Cloud cloud = cloudFrom(view, "classify", &name, inputForm(kind, shape, "classify"));
    learning::FeatureTable t = layout_;
    std::vector<learning::Prediction> p;
    {
      py::gil_scoped_release release;
      t.rows = {learning::describeCloud(cloud, options_, layout_)};
      if (t.rows[0].keypoints < 0 && !t.rows[0].problem.empty() && !t.rows[0].no_object)
        throw Error(name + ": " + t.rows[0].problem);
      std::lock_guard<std::mutex> lock(predict_mutex_);  // one prediction at a time, as the recogniser
      p = learning::predictRows(model_, t, source_);
    }
    Classification c;
    const auto& classes = model_.info.classes;
    const learning::Prediction& pr = p.at(0);
    c.cls = learning::answerLabel(model_.info, pr);
    c.answer = learning::answerName(pr.answer);
    if (pr.best >= 0) {
      c.best = classes.at(static_cast<std::size_t>(pr.best));
      c.probability = pr.probabilities.at(static_cast<std::size_t>(pr.best));
      for (std::size_t k = 0; k < classes.size(); ++k) c.probabilities.emplace_back(classes[k], pr.probabilities[k]);
    }
    if (model_.info.open_set.enabled()) {
      c.threshold = model_.info.open_set.threshold;
      if (pr.best >= 0 && std::isfinite(pr.score)) c.score = pr.score;
    }
    c.keypoints = t.rows[0].keypoints;
    c.problem = t.rows[0].problem;
    return c;
  }

  const learning::ModelInfo& info() const { return model_.info; }
  const std::string& source() const { return source_; }

 private:
  std::string source_;
  learning::Model model_;
  learning::FeatureTable layout_;
  DescriptorOptions options_;
  std::mutex predict_mutex_;
};

}  // namespace

py::object wrapModel(learning::Model model, const std::string& source) {
  return py::cast(std::make_unique<PyModel>(std::move(model), source));
}

void bindModel(py::module_& m) {
  py::class_<Classification>(m, "Classification",
                             "A view's answer, class probabilities and open-set score (keyturn classify --json)")
      .def_readonly("cls", &Classification::cls,
                    "the answer: the most probable class, 'unknown' (an open-set model's score below its threshold) "
                    "or 'no object' (too little in view to describe)")
      .def_readonly("answer", &Classification::answer, "'class', 'unknown' or 'no object'")
      .def_readonly("best", &Classification::best, "the most probable class, even when the answer is 'unknown'")
      .def_readonly("probability", &Classification::probability, "the most probable class's")
      .def_property_readonly("probabilities", [](const Classification& c) {
        py::dict d;
        for (const auto& [k, v] : c.probabilities) d[py::str(k)] = v;
        return d;
      }, "class → probability, the model's class order (empty for no object)")
      .def_readonly("score", &Classification::score, "the open-set score (None for a closed-set model or no object)")
      .def_readonly("threshold", &Classification::threshold, "the model's open-set threshold (None: closed-set)")
      .def_readonly("keypoints", &Classification::keypoints, "K")
      .def_readonly("problem", &Classification::problem, "what was thin or missing ('' when nothing)")
      .def(py::pickle(
          [](const Classification& c) {
            return py::make_tuple(c.cls, c.probability, c.probabilities, c.keypoints, c.problem, c.answer, c.best,
                                  c.score, c.threshold);
          },
          [](const py::tuple& t) {
            if (t.size() != 5 && t.size() != 9) throw py::value_error("Classification: not a pickled keyturn.Classification");
            Classification c;
            c.cls = t[0].cast<std::string>();
            c.probability = t[1].cast<double>();
            c.probabilities = t[2].cast<std::vector<std::pair<std::string, double>>>();
            c.keypoints = t[3].cast<int>();
            c.problem = t[4].cast<std::string>();
            c.best = c.cls;  // a pickle from before open-set answers: always a class
            if (t.size() == 9) {
              c.answer = t[5].cast<std::string>();
              c.best = t[6].cast<std::string>();
              c.score = t[7].cast<std::optional<double>>();
              c.threshold = t[8].cast<std::optional<double>>();
            }
            return c;
          }))
      .def("__eq__", [](const Classification& a, const Classification& b) {
        return a.cls == b.cls && a.probability == b.probability && a.probabilities == b.probabilities &&
               a.keypoints == b.keypoints && a.problem == b.problem && a.answer == b.answer && a.best == b.best &&
               a.score == b.score && a.threshold == b.threshold;
      })
      .def("__repr__", [](const Classification& c) {
        std::string r = "<keyturn.Classification " + c.cls;
        if (c.answer == "class") r += " " + std::to_string(c.probability);
        if (c.answer == "unknown") r += " (best " + c.best + " " + std::to_string(c.probability) + ")";
        if (c.score && c.threshold)
          r += ", score " + std::to_string(*c.score) + (c.answer == "class" ? " >= " : " < ") + std::to_string(*c.threshold);
        return r + ">";
      });

  py::class_<PyModel>(m, "Model", "A model folder written by keyturn train (model.json and the classifier's file)")
      .def(py::init([](const py::object& path) {
             return std::make_unique<PyModel>(py::str(py::module_::import("os").attr("fspath")(path)));
           }),
           py::arg("path"),
           "Loads the model; raises FileNotFoundError for a missing folder, keyturn.Error naming the file when it is "
           "corrupt")
      .def("classify", &PyModel::classify, py::arg("view"), py::kw_only(), py::arg("kind") = "auto",
           py::arg("shape") = py::none(),
           "classify(view, *, kind='auto', shape=None) -> Classification\n\nview: a PCD/PLY path, a keyturn.Cloud, an "
           "Open3D point cloud or an N × 3 / H × W × 3 array (kind and shape as for describe). Described with the "
           "model's own parameters, as keyturn classify does (GIL released). A view too empty to describe is "
           "answered 'no object'; with an open-set model, a view unlike every trained class 'unknown'.")
      .def("save", [](PyModel& p, const py::object& path) { p.save(py::str(py::module_::import("os").attr("fspath")(path))); },
           py::arg("path"),
           "save(path)\n\nWrites the model folder (model.json and the classifier's file), as keyturn train does; "
           "keyturn classify and keyturn.Model read it.")
      .def_property_readonly("classes", [](const PyModel& p) { return p.info().classes; })
      .def_property_readonly("blocks", [](const PyModel& p) { return p.info().blocks; }, "feature blocks, in order")
      .def_property_readonly("inputs", [](const PyModel& p) { return p.info().inputs; })
      .def_property_readonly("spec", [](const PyModel& p) { return p.info().spec; }, "its feature specification")
      .def_property_readonly("classifier", [](const PyModel& p) { return p.info().params.kind; })
      .def_property_readonly("open_set", [](const PyModel& p) -> py::object {
        const learning::OpenSet& o = p.info().open_set;
        if (!o.enabled()) return py::none();
        py::dict d;
        d["method"] = o.method, d["threshold"] = o.threshold, d["false_accept"] = o.false_accept;
        d["rule"] = o.rule;
        return std::move(d);
      }, "{'method', 'threshold', 'false_accept', 'rule'} of an open-set model (rule: how its threshold was "
         "calibrated, 'pooled' or 'per-group'); None for a closed-set one")
      .def("__repr__", [](const PyModel& p) {
        return "<keyturn.Model " + p.source() + ", " + std::to_string(p.info().classes.size()) + " classes>";
      });
}

}  // namespace keyturn::python
