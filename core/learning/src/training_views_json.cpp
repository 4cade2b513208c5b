#include "training_views_json.h"

#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <tuple>

#include "keyturn/core/checked_integer.h"
#include "keyturn/core/error.h"
#include "keyturn/core/json_error.h"
#include "keyturn/core/json_integer.h"

namespace keyturn::learning {

using nlohmann::json;

json trainingViewsJson(const TrainingViews& v) {
  std::map<std::tuple<std::string, std::string, std::string, std::string>, int> index;
  json captures = json::array(), views = json::array();
  for (const auto& t : v.views) {
    const auto key = std::make_tuple(t.cls, t.instance, t.elevation, t.camera);
    auto it = index.find(key);
    if (it == index.end()) {
      it = index.emplace(key, static_cast<int>(index.size())).first;
      json capture = {t.cls, t.instance, t.elevation};
      if (!t.camera.empty()) capture.push_back(t.camera);
      captures.push_back(std::move(capture));
    }
    json row = {it->second, std::isfinite(t.azimuth_deg) ? json(t.azimuth_deg) : json(nullptr)};
    if (!t.missing.empty()) row.push_back(t.missing);
    views.push_back(std::move(row));
  }
  return {{"label", v.label == LabelKind::Category ? "category" : "instance"},
          {"open_set_groups", v.open_set_groups},
          {"open_set_seed", v.open_set_seed},
          {"captures", std::move(captures)},
          {"views", std::move(views)}};
}

TrainingViews parseTrainingViewsJson(const json& j, std::size_t references, int inputs, const std::string& source) {
  const std::string where = source + ": training_views";
  TrainingViews out;
  try {
    try {
      out.label = parseLabelKind(j.at("label").get<std::string>());
    } catch (const Error& e) {
      throw Error(where + ": " + e.what());
    }
    out.open_set_groups = jsonInteger(j, "open_set_groups", 2, 1000, where);
    out.open_set_seed = jsonInteger(j, "open_set_seed", std::uint64_t{0}, std::numeric_limits<std::uint64_t>::max(), where);
    std::vector<std::array<std::string, 4>> captures;
    for (const auto& c : j.at("captures")) {
      if (!c.is_array() || c.size() < 3 || c.size() > 4)
        throw Error(where + ": a capture is not [category, instance, elevation] or [category, instance, elevation, camera]");
      captures.push_back({c[0].get<std::string>(), c[1].get<std::string>(), c[2].get<std::string>(),
                          c.size() == 4 ? c[3].get<std::string>() : std::string()});
    }
    const auto& views = j.at("views");
    if (!views.is_array() || views.size() != references)
      throw Error(where + ": " + std::to_string(views.is_array() ? views.size() : 0) + " views for " +
                  std::to_string(references) + " open_set references (one each)");
    for (std::size_t i = 0; i < views.size(); ++i) {
      const auto& row = views[i];
      const std::string at = where + ": view " + std::to_string(i);
      if (!row.is_array() || row.size() < 2 || row.size() > 3 || !row[0].is_number())
        throw Error(at + " is not [capture, azimuth] or [capture, azimuth, missing columns]");
      const auto c = integerIn(row[0].get<double>(), std::size_t{0}, captures.empty() ? 0 : captures.size() - 1);
      if (!c || captures.empty()) throw Error(at + " names no capture of the " + std::to_string(captures.size()) + " listed");
      TrainingView v{captures[*c][0], captures[*c][1], captures[*c][2], std::nan(""), {}, captures[*c][3]};
      if (!row[1].is_null()) {
        v.azimuth_deg = row[1].get<double>();
        if (!std::isfinite(v.azimuth_deg)) throw Error(at + ": the azimuth must be finite or null");
      }
      if (row.size() == 3)
        for (const auto& k : row[2]) {
          const auto col = k.is_number() ? integerIn(k.get<double>(), 0, inputs - 1) : std::nullopt;
          if (!col) throw Error(at + ": a missing column outside 0.." + std::to_string(inputs - 1));
          v.missing.push_back(*col);
        }
      out.views.push_back(std::move(v));
    }
  } catch (const json::exception& e) {
    throw Error(where + ": " + jsonErrorText(e));
  }
  return out;
}

}  // namespace keyturn::learning
