#include "open_set_json.h"

#include <cmath>
#include <limits>
#include <map>

#include "keyturn/core/checked_integer.h"
#include "keyturn/core/error.h"
#include "keyturn/core/json_error.h"
#include "keyturn/core/json_integer.h"
#include "reference_value_json.h"

namespace keyturn::learning {

using nlohmann::json;

json openSetJson(const OpenSet& s) {
  json j = {{"method", s.method},
            {"threshold", s.threshold},
            {"false_accept", s.false_accept},
            {"calibration", {{"unknown_views", s.calibration_views}, {"groups", s.calibration_groups}}}};
  if (s.rule != "pooled") j["calibration"]["rule"] = s.rule;  // absent: pooled (every model before 2026-12-07)
  if (std::isfinite(s.turn_threshold)) {
    j["turn_threshold"] = s.turn_threshold;
    j["calibration"]["unknown_turns"] = s.calibration_turns;
  }
  if (!keepsReferences(s.method)) return j;
  if (s.method == "knn-relative") j["class_scale"] = s.class_scale;
  if (s.method == "knn-relative" && s.class_scale_power != 1)  // absent: each class's own scale
    j["class_scale_power"] = s.class_scale_power;
  if (s.method == "knn-relative" && s.class_spread != "views")  // absent: each class's views' spread
    j["class_spread"] = s.class_spread;
  if (s.method == "knn-relative" && s.scale_by != "pooled") {  // absent: the pooled scale (models before issue 47's)
    j["scale_by"] = s.scale_by;
    j["camera_scale"] = s.camera_scale;
  }
  j["neighbours"] = s.neighbours;
  if (s.distance != "rms") j["distance"] = s.distance;  // absent: rms (every model before 2026-12-06)
  j["mean"] = s.mean;
  j["scale"] = s.scale;
  json refs = json::array();
  for (Eigen::Index r = 0; r < s.references.rows(); ++r) {
    json row = json::array({s.reference_class[static_cast<std::size_t>(r)]});
    for (Eigen::Index k = 0; k < s.references.cols(); ++k) row.push_back(referenceValue(s.references(r, k)));
    refs.push_back(std::move(row));
  }
  j["references"] = std::move(refs);
  return j;
}

namespace {

// A named choice of the sidecar, checked: its error names the file and the open_set object.
std::string choiceOf(const json& j, const char* key, void (*check)(const std::string&), const std::string& where) {
  const std::string value = j.at(key).get<std::string>();
  try {
    check(value);
  } catch (const Error& e) {
    throw Error(where + ": " + e.what());
  }
  return value;
}

}  // namespace

OpenSet parseOpenSetJson(const json& j, int inputs, int classes, const std::string& source) {
  const std::string where = source + ": open_set";
  OpenSet s;
  try {
    s.method = choiceOf(j, "method", checkOpenSetMethod, where);
    s.threshold = j.at("threshold").get<double>();
    s.false_accept = j.at("false_accept").get<double>();
    if (!std::isfinite(s.threshold) || !(s.false_accept >= 0 && s.false_accept < 1))
      throw Error(where + ": threshold must be finite and false_accept within [0, 1)");
    if (j.contains("calibration")) {
      const auto& c = j.at("calibration");
      s.calibration_views = jsonInteger(c, "unknown_views", 0, std::numeric_limits<int>::max(), where);
      s.calibration_groups = jsonInteger(c, "groups", 0, std::numeric_limits<int>::max(), where);
      if (c.contains("rule")) s.rule = choiceOf(c, "rule", checkOpenSetRule, where);
      if (c.contains("unknown_turns"))
        s.calibration_turns = jsonInteger(c, "unknown_turns", 0, std::numeric_limits<int>::max(), where);
    }
    if (j.contains("turn_threshold")) {
      s.turn_threshold = j.at("turn_threshold").get<double>();
      if (!std::isfinite(s.turn_threshold)) throw Error(where + ": turn_threshold must be finite");
    }
    if (!keepsReferences(s.method)) return s;
    if (s.method == "knn-relative") {
      s.class_scale = j.at("class_scale").get<std::vector<float>>();
      if (s.class_scale.size() != static_cast<std::size_t>(classes))
        throw Error(where + ": knn-relative needs class_scale of " + std::to_string(classes) + " values");
      for (float v : s.class_scale)
        if (!(v > 0) || !std::isfinite(v)) throw Error(where + ": class_scale values must be positive");
      if (j.contains("class_scale_power")) {
        s.class_scale_power = j.at("class_scale_power").get<double>();
        if (!(s.class_scale_power >= 0 && s.class_scale_power <= 1))
          throw Error(where + ": class_scale_power must be within [0, 1]");
      }
      if (j.contains("class_spread")) s.class_spread = choiceOf(j, "class_spread", checkOpenSetSpread, where);
      if (j.contains("scale_by")) {
        s.scale_by = choiceOf(j, "scale_by", checkOpenSetScale, where);
        if (j.contains("camera_scale")) s.camera_scale = j.at("camera_scale").get<std::map<std::string, float>>();
        for (const auto& [camera, v] : s.camera_scale)
          if (!(v > 0) || !std::isfinite(v)) throw Error(where + ": camera_scale of '" + camera + "' must be positive");
      }
    }
    s.neighbours = jsonInteger(j, "neighbours", 1, 1 << 16, where);
    if (j.contains("distance")) s.distance = choiceOf(j, "distance", checkOpenSetDistance, where);
    s.mean = j.at("mean").get<std::vector<float>>();
    s.scale = j.at("scale").get<std::vector<float>>();
    const auto& refs = j.at("references");
    if (s.mean.size() != static_cast<std::size_t>(inputs) || s.scale.size() != s.mean.size() || !refs.is_array() ||
        refs.empty())
      throw Error(where + ": knn needs mean and scale of " + std::to_string(inputs) + " values and references");
    s.references.resize(static_cast<Eigen::Index>(refs.size()), inputs);
    for (std::size_t r = 0; r < refs.size(); ++r) {
      const auto& row = refs[r];
      if (!row.is_array() || row.size() != static_cast<std::size_t>(inputs) + 1)
        throw Error(where + ": reference " + std::to_string(r) + " is not [class, " + std::to_string(inputs) + " values]");
      const auto c = row[0].is_number() ? integerIn(row[0].get<double>(), 0, classes - 1) : std::nullopt;
      if (!c) throw Error(where + ": reference " + std::to_string(r) + " names no class 0.." + std::to_string(classes - 1));
      s.reference_class.push_back(*c);
      for (int k = 0; k < inputs; ++k) s.references(static_cast<Eigen::Index>(r), k) = row[static_cast<std::size_t>(k) + 1].get<float>();
    }
    for (float v : s.scale)
      if (!(v > 0) || !std::isfinite(v)) throw Error(where + ": scale values must be positive");
  } catch (const json::exception& e) {
    throw Error(where + ": " + jsonErrorText(e));
  }
  return s;
}

}  // namespace keyturn::learning
