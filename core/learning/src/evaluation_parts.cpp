#include "keyturn/learning/evaluation_parts.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>

#include "classifier_params_json.h"
#include "keyturn/core/error.h"
#include "keyturn/core/fnv1a.h"
#include "keyturn/core/json_error.h"
#include "keyturn/core/json_file.h"
#include "keyturn/core/json_integer.h"

namespace keyturn::learning {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr const char* kFormat = "keyturn-evaluation-part";
constexpr int kVersion = 1;

// Everything that decides which trainings the run has and what they give; the parts of one
// evaluation agree on all of it. The dataset's path is left out (a merge may name it another way).
json planKey(const EvaluationRun& run) {
  const EvaluationPlan& p = run.plan;
  json params = classifierParamsJson(p.params);
  params.erase("classifier");  // each row's own
  json tables = json::object();
  for (const auto& [bins, t] : run.tables) {
    std::string ids;
    for (const auto& r : t.rows) ids += r.id + "\n";
    char hash[17];
    std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>(fnv1a(ids)));
    tables[std::to_string(bins)] = {{"feature_spec", t.spec}, {"views", t.rows.size()}, {"view_ids_fnv1a", hash}};
  }
  return {{"feature_sets", p.feature_sets}, {"classifiers", p.classifiers}, {"protocols", p.protocols},
          {"bins", p.bins},                 {"split_seed", p.split_seed},   {"params", params},
          {"tables", tables},               {"trainings", run.totalFolds()}, {"inner_folds", p.inner_folds},
          {"train_extra", p.train_extra},
          // --label: parts judged by other labels are another run
          {"label", p.label ? (*p.label == LabelKind::Category ? "category" : "instance") : "each protocol's own"},
          // the open-set protocol's calibration: parts calibrated otherwise are another run
          {"open_set", {{"methods", p.open_set.methods}, {"false_accept", p.open_set.false_accept},
                        {"groups", p.open_set.groups}, {"neighbours", p.open_set.neighbours},
                        {"rule", p.open_set.rule}}}};
}

std::string differences(const json& theirs, const json& mine) {
  std::string keys;
  for (const auto& [k, v] : mine.items())
    if (!theirs.contains(k) || theirs.at(k) != v) keys += (keys.empty() ? "" : ", ") + k;
  return keys.empty() ? "the plan" : keys;
}

// Reads one part into the run's rows; `seen` marks the trainings already filled.
double readPart(const std::string& path, int shard, int shards, EvaluationRun& run,
                std::vector<std::vector<bool>>& seen) {
  const json j = readJsonFile(path, JsonShape::Object);
  const std::size_t most = std::numeric_limits<int>::max();
  try {
    if (!j.is_object() || j.value("format", "") != kFormat) throw Error(path + ": not a keyturn evaluation part");
    if (j.at("version") != kVersion)
      throw Error(path + ": evaluation part version " + j.at("version").dump() + " is not supported (expected 1)");
    if (jsonInteger(j, "shard", std::size_t{1}, most, path) != static_cast<std::size_t>(shard + 1) ||
        jsonInteger(j, "shards", std::size_t{1}, most, path) != static_cast<std::size_t>(shards))
      throw Error(path + ": says it is part " + j.at("shard").dump() + " of " + j.at("shards").dump());
    const json mine = planKey(run);
    if (j.at("plan") != mine)
      throw Error(path + ": made by another evaluation (differs in " + differences(j.at("plan"), mine) +
                  "); merge with the options the parts were run with");
    for (const auto& f : j.at("folds")) {
      const std::size_t r = jsonInteger(f, "row", std::size_t{0}, run.rows.size() - 1, path);
      EvaluationRow& row = run.rows[r];
      const std::size_t k = jsonInteger(f, "fold", std::size_t{0}, most, path);
      if (k >= row.proto->folds.size()) throw Error(path + ": row " + std::to_string(r) + " has no fold " + std::to_string(k));
      const std::string name = f.at("name").get<std::string>();
      if (name != row.proto->folds[k].name || seen[r][k])
        throw Error(path + ": fold '" + name + "' of row " + std::to_string(r) + " is not the run's or is there twice");
      FoldOutcome o;
      o.name = name;
      o.train_views = jsonInteger(f, "train_views", std::size_t{0}, most, path);
      o.test_views = jsonInteger(f, "test_views", std::size_t{0}, most, path);
      o.correct = jsonInteger(f, "correct", std::size_t{0}, o.test_views, path);
      o.train_ms = f.at("train_ms").get<double>();
      o.predict_ms = f.at("predict_ms").get<double>();
      const int classes = static_cast<int>(row.proto->labels.names.size());
      for (const auto& c : f.at("confusion")) {
        if (!c.is_array() || c.size() != 3) throw Error(path + ": a confusion cell is [truth, predicted, count]");
        const json cell{{"t", c[0]}, {"p", c[1]}, {"n", c[2]}};
        o.confusion.push_back({jsonInteger(cell, "t", 0, classes - 1, path), jsonInteger(cell, "p", 0, classes - 1, path),
                               jsonInteger(cell, "n", 0, static_cast<int>(o.test_views), path)});
      }
      o.twin_views = jsonInteger(f, "twin_views", std::size_t{0}, std::size_t{0}, most, path);
      if (f.contains("chosen")) {
        o.chosen = f.at("chosen").get<std::string>();
        o.inner_accuracy = f.at("inner_accuracy").get<std::vector<double>>();
      }
      if (f.contains("open_set")) {
        const auto& os = f.at("open_set");
        o.unknown_views = jsonInteger(os, "unknown_views", std::size_t{0}, most, path);
        if (os.contains("fused_known")) {
          o.fused_known = jsonInteger(os, "fused_known", std::size_t{0}, most, path);
          o.fused_unknown = jsonInteger(os, "fused_unknown", std::size_t{0}, most, path);
          o.fused_known_closed_correct = jsonInteger(os, "fused_known_closed_correct", std::size_t{0}, o.fused_known, path);
        }
        for (const auto& m : os.at("methods")) {
          OpenSetFoldOutcome mo;
          mo.method = m.at("method").get<std::string>();
          mo.threshold = m.at("threshold").get<double>();
          mo.known_accepted = jsonInteger(m, "known_accepted", std::size_t{0}, o.test_views, path);
          mo.known_correct = jsonInteger(m, "known_correct", std::size_t{0}, mo.known_accepted, path);
          mo.unknown_accepted = jsonInteger(m, "unknown_accepted", std::size_t{0}, o.unknown_views, path);
          mo.known_scores = m.at("known_scores").get<std::vector<double>>();
          mo.unknown_scores = m.at("unknown_scores").get<std::vector<double>>();
          if (m.contains("fused_known_correct")) {  // the views had angles
            mo.fused_known_correct = jsonInteger(m, "fused_known_correct", std::size_t{0}, most, path);
            mo.fused_unknown_accepted = jsonInteger(m, "fused_unknown_accepted", std::size_t{0}, most, path);
          }
          if (mo.known_scores.size() != o.test_views || mo.unknown_scores.size() != o.unknown_views)
            throw Error(path + ": fold '" + name + "': open-set scores for another number of views");
          o.open_set.push_back(std::move(mo));
        }
      }
      row.ev.folds[k] = o;
      seen[r][k] = true;
    }
    return j.at("seconds").get<double>();
  } catch (const json::exception& e) {
    throw Error(path + ": " + jsonErrorText(e));
  }
}

}  // namespace

std::string evaluationPartPath(const std::string& out, int shard, int shards) {
  return (fs::path(out) / "parts" / ("part-" + std::to_string(shard + 1) + "-of-" + std::to_string(shards) + ".json"))
      .string();
}

std::string evaluationPartJson(const EvaluationRun& run, int shard, int shards) {
  json folds = json::array();
  for (const FoldJob& job : foldJobs(run, shard, shards)) {
    const FoldOutcome& o = run.rows[job.row].ev.folds[job.fold];
    json cells = json::array();
    for (const auto& c : o.confusion) cells.push_back({c.truth, c.predicted, c.count});
    folds.push_back({{"row", job.row},           {"fold", job.fold},         {"name", o.name},
                     {"train_views", o.train_views}, {"test_views", o.test_views}, {"correct", o.correct},
                     {"train_ms", o.train_ms},   {"predict_ms", o.predict_ms}, {"confusion", cells}});
    if (!o.chosen.empty()) folds.back()["chosen"] = o.chosen, folds.back()["inner_accuracy"] = o.inner_accuracy;
    if (o.twin_views) folds.back()["twin_views"] = o.twin_views;
    if (!o.open_set.empty()) {
      json methods = json::array();
      for (const auto& m : o.open_set)
        methods.push_back({{"method", m.method}, {"threshold", m.threshold}, {"known_accepted", m.known_accepted},
                           {"known_correct", m.known_correct}, {"unknown_accepted", m.unknown_accepted},
                           {"known_scores", m.known_scores}, {"unknown_scores", m.unknown_scores},
                           {"fused_known_correct", m.fused_known_correct},
                           {"fused_unknown_accepted", m.fused_unknown_accepted}});
      folds.back()["open_set"] = {{"unknown_views", o.unknown_views}, {"methods", methods},
                                  {"fused_known", o.fused_known}, {"fused_unknown", o.fused_unknown},
                                  {"fused_known_closed_correct", o.fused_known_closed_correct}};
    }
  }
  const json j{{"format", kFormat}, {"version", kVersion}, {"shard", shard + 1}, {"shards", shards},
               {"plan", planKey(run)},  {"seconds", run.total_s}, {"folds", folds}};
  return j.dump(1) + "\n";
}

int mergeEvaluationParts(EvaluationRun& run, const std::string& out) {
  const fs::path dir = fs::path(out) / "parts";
  const std::regex part_re(R"(part-(\d+)-of-(\d+)\.json)");
  std::map<int, std::map<int, std::string>> sets;  // N → I → file
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    std::smatch m;
    const std::string name = e.path().filename().string();
    if (std::regex_match(name, m, part_re) && m[1].length() < 9 && m[2].length() < 9)
      sets[std::stoi(m[2])][std::stoi(m[1]) - 1] = e.path().string();
  }
  if (sets.empty()) throw Error(dir.string() + ": no evaluation parts (part-I-of-N.json: the shards of the evaluation run first)");
  std::vector<int> complete;
  for (const auto& [n, files] : sets) {
    bool all = n > 0 && static_cast<int>(files.size()) == n;
    for (int i = 0; all && i < n; ++i) all = files.count(i) > 0;
    if (all) complete.push_back(n);
  }
  if (complete.size() > 1)
    throw Error(dir.string() + ": complete sets of " + std::to_string(complete[0]) + " and " +
                std::to_string(complete[1]) + " parts; remove the stale one");
  if (complete.empty()) {
    const auto& [n, files] = *sets.rbegin();
    std::string missing;
    for (int i = 0; i < n; ++i)
      if (!files.count(i)) missing += (missing.empty() ? "" : ", ") + fs::path(evaluationPartPath(out, i, n)).filename().string();
    throw Error(dir.string() + ": " + std::to_string(files.size()) + " of " + std::to_string(n) + " parts, missing " +
                missing);
  }
  const int n = complete.front();
  std::vector<std::vector<bool>> seen;
  for (auto& r : run.rows) {
    r.ev.folds.assign(r.proto->folds.size(), {});
    seen.emplace_back(r.proto->folds.size(), false);
  }
  double seconds = 0;
  for (const auto& [i, file] : sets.at(n)) seconds += readPart(file, i, n, run, seen);
  for (std::size_t r = 0; r < run.rows.size(); ++r)
    for (std::size_t k = 0; k < seen[r].size(); ++k)
      if (!seen[r][k])
        throw Error(dir.string() + ": no part holds fold '" + run.rows[r].proto->folds[k].name + "' of " +
                    run.rows[r].features + ", " + run.rows[r].classifier + ", " + run.rows[r].protocol);
  for (auto& r : run.rows) r.ev.confusion = sumConfusion(r.ev.folds, static_cast<int>(r.proto->labels.names.size()));
  run.total_s += seconds;  // the parts' own times, summed
  return n;
}

}  // namespace keyturn::learning
