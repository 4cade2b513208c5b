#include "pose_references_json.h"

#include <cmath>

#include "keyturn/core/error.h"
#include "keyturn/core/json_error.h"
#include "keyturn/core/json_integer.h"
#include "reference_value_json.h"

namespace keyturn::learning {

namespace {

// The rows, classes and standardisation the sidecar would write for both are the same.
bool sameRows(const PoseReferences& r, const OpenSet& s) {
  if (!keepsReferences(s.method) || r.mean != s.mean || r.scale != s.scale || r.reference_class != s.reference_class ||
      r.references.rows() != s.references.rows() || r.references.cols() != s.references.cols())
    return false;
  for (Eigen::Index i = 0; i < r.references.rows(); ++i)
    for (Eigen::Index k = 0; k < r.references.cols(); ++k)
      if (referenceValue(r.references(i, k)) != referenceValue(s.references(i, k))) return false;
  return true;
}

}  // namespace

nlohmann::json poseReferencesJson(const PoseReferences& r, const OpenSet* open_set) {
  if (open_set && sameRows(r, *open_set))
    return {{"bins", r.bins}, {"sigma", r.sigma}, {"rows_of", "open_set"}, {"reference_bins", r.reference_bin}};
  nlohmann::json refs = nlohmann::json::array();
  for (Eigen::Index i = 0; i < r.references.rows(); ++i) {
    nlohmann::json row = {r.reference_class[static_cast<std::size_t>(i)], r.reference_bin[static_cast<std::size_t>(i)]};
    for (Eigen::Index k = 0; k < r.references.cols(); ++k) row.push_back(referenceValue(r.references(i, k)));
    refs.push_back(std::move(row));
  }
  return {{"bins", r.bins}, {"sigma", r.sigma}, {"mean", r.mean}, {"scale", r.scale}, {"references", std::move(refs)}};
}

PoseReferences parsePoseReferencesJson(const nlohmann::json& j, int inputs, int classes, const std::string& source,
                                       const OpenSet* open_set) {
  const std::string where = source + ": pose_references";
  PoseReferences r;
  r.classes = classes;
  try {
    r.bins = jsonInteger(j, "bins", 4, 3600, where);
    r.sigma = j.at("sigma").get<double>();
    if (!(r.sigma > 0) || !std::isfinite(r.sigma)) throw Error(where + ": sigma must be positive");
    if (j.contains("rows_of")) {
      if (j.at("rows_of") != "open_set" || !open_set || !keepsReferences(open_set->method))
        throw Error(where + ": rows_of names no knn open_set of this model to take the rows from");
      const auto bins = j.at("reference_bins").get<std::vector<int>>();
      if (bins.size() != static_cast<std::size_t>(open_set->references.rows()))
        throw Error(where + ": " + std::to_string(bins.size()) + " reference_bins for " +
                    std::to_string(open_set->references.rows()) + " open_set rows");
      for (int b : bins)
        if (b < 0 || b >= r.bins) throw Error(where + ": reference bin " + std::to_string(b) + " out of range");
      r.mean = open_set->mean, r.scale = open_set->scale;
      r.references = open_set->references, r.reference_class = open_set->reference_class, r.reference_bin = bins;
      return r;
    }
    r.mean = j.at("mean").get<std::vector<float>>();
    r.scale = j.at("scale").get<std::vector<float>>();
    const auto& refs = j.at("references");
    if (r.mean.size() != static_cast<std::size_t>(inputs) || r.scale.size() != r.mean.size() || !refs.is_array() ||
        refs.empty())
      throw Error(where + ": needs mean and scale of " + std::to_string(inputs) + " values and references");
    r.references.resize(static_cast<Eigen::Index>(refs.size()), inputs);
    for (std::size_t i = 0; i < refs.size(); ++i) {
      const auto& row = refs[i];
      if (!row.is_array() || row.size() != static_cast<std::size_t>(inputs) + 2 || !row[0].is_number_integer() ||
          !row[1].is_number_integer())
        throw Error(where + ": reference " + std::to_string(i) + " is not [class, bin, " + std::to_string(inputs) + " values]");
      const int c = row[0].get<int>(), b = row[1].get<int>();
      if (c < 0 || c >= classes || b < 0 || b >= r.bins)
        throw Error(where + ": reference " + std::to_string(i) + " has class " + std::to_string(c) + " or bin " +
                    std::to_string(b) + " out of range");
      r.reference_class.push_back(c);
      r.reference_bin.push_back(b);
      for (int k = 0; k < inputs; ++k) r.references(static_cast<Eigen::Index>(i), k) = row[static_cast<std::size_t>(k) + 2].get<float>();
    }
    for (float v : r.scale)
      if (!(v > 0) || !std::isfinite(v)) throw Error(where + ": scale values must be positive");
  } catch (const nlohmann::json::exception& e) {
    throw Error(where + ": " + jsonErrorText(e));
  }
  return r;
}

}  // namespace keyturn::learning
