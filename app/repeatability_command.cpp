// keyturn repeatability: absolute and relative keypoint repeatability against ε
// for several detectors over pairs of views with known relative poses (a
// calibrated keyturn dataset, or a pose list), optionally refined by ICP.
#include <Eigen/Geometry>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "commands.h"
#include "keyturn/core/cloud_io.h"
#include "keyturn/core/error.h"
#include "keyturn/core/filter.h"
#include "keyturn/core/keypoint_detectors.h"
#include "keyturn/core/pose_list.h"
#include "keyturn/core/radius_search.h"
#include "keyturn/core/repeatability.h"
#include "keyturn/rig/dataset.h"
#include "keyturn/core/durable_file.h"
#include "keyturn/rig/sidecars.h"
#include "keyturn/ui/line_chart.h"
#include "progress.h"

namespace fs = std::filesystem;

namespace keyturn::app {
namespace {

struct RepArgs {
  std::string input, out;
  std::string detectors = "iss,harris3d,sift3d,uniform";
  std::string eps = "0.5:3:0.25";
  std::string pairs = "consecutive";
  bool icp = false, json = false, no_filter = false;
};

struct View {
  std::string file, group;
  double angle_deg = 0;               // turntable angle (datasets)
  Eigen::Matrix4d view_from_common;   // camera of this view ← the common frame
  PointSet set;
  double res = 0;
  std::map<Detector, std::vector<Eigen::Vector3f>> kp;
  std::map<Detector, double> ms;
};

std::vector<double> parseEps(const std::string& s) {
  std::vector<double> out;
  try {
    if (s.find(':') != std::string::npos) {
      double a, b, step;
      char c1, c2;
      std::istringstream ss(s);
      if (!(ss >> a >> c1 >> b >> c2 >> step) || c1 != ':' || c2 != ':' || step <= 0 || b < a) throw std::invalid_argument(s);
      for (double e = a; e <= b + 1e-9; e += step) out.push_back(e);
    } else {
      std::istringstream ss(s);
      for (std::string t; std::getline(ss, t, ',');) out.push_back(std::stod(t));
    }
  } catch (const std::exception&) {
    throw Error("--eps: expected START:STOP:STEP or a comma list of multiples of the resolution, got '" + s + "'");
  }
  if (out.empty()) throw Error("--eps: no values");
  return out;
}

std::vector<View> viewsFromDataset(const std::string& root) {
  std::vector<View> out;
  for (const auto& r : rig::Dataset::readManifest(root)) {
    View v;
    v.file = root + "/" + r.pcd();
    v.group = r.key.cls + "/" + r.key.instance + "/e" + r.key.elevation;
    v.angle_deg = r.measured_deg;
    const auto T = rig::readViewTransform(root + "/" + r.sidecar());
    if (!T)
      throw Error(root + ": " + r.sidecar() +
                  " has no camera_from_turntable: capture with --calibration (keyturn calibrate-axis), or give a pose list");
    // The sidecar's camera ← turntable at this view's angle maps the object's own
    // (table-fixed) coordinates into this camera: the object frame is the common frame.
    v.view_from_common = *T;
    out.push_back(std::move(v));
  }
  return out;
}

std::vector<View> viewsFromPoseList(const std::string& path) {
  std::vector<View> out;
  for (const auto& e : readPoseList(path)) {
    View v;
    v.file = e.file;
    v.group = fs::path(path).filename().string();
    v.view_from_common = e.world_from_view.inverse();
    out.push_back(std::move(v));
  }
  return out;
}

double rotationBetween(const View& a, const View& b, bool dataset) {
  if (dataset) {
    double d = std::fmod(std::abs(a.angle_deg - b.angle_deg), 360.0);
    return d > 180 ? 360 - d : d;
  }
  const Eigen::Matrix3d r = (b.view_from_common * a.view_from_common.inverse()).topLeftCorner<3, 3>();
  return Eigen::AngleAxisd(r).angle() * 180 / M_PI;
}

int runRepeatability(const RepArgs& a) {
  std::vector<Detector> detectors;
  {
    std::istringstream ss(a.detectors);
    for (std::string t; std::getline(ss, t, ',');) detectors.push_back(parseDetector(t));
  }
  const std::vector<double> eps = parseEps(a.eps);
  const bool dataset = fs::is_directory(a.input);
  std::vector<View> views = dataset ? viewsFromDataset(a.input) : viewsFromPoseList(a.input);
  if (views.size() < 2) throw Error(a.input + ": repeatability needs at least 2 views");

  // Pairs within each group (one object at one elevation, or one pose list).
  std::vector<std::pair<int, int>> pairs;
  double within = 360;
  std::string rule = a.pairs;
  if (rule.rfind("all-within:", 0) == 0) {
    within = std::stod(rule.substr(11));
    rule = "all-within";
  }
  if (rule != "consecutive" && rule != "from-first" && rule != "all-within")
    throw Error("--pairs: expected consecutive, from-first or all-within:DEG, got '" + a.pairs + "'");
  std::map<std::string, std::vector<int>> groups;
  for (int i = 0; i < static_cast<int>(views.size()); ++i) groups[views[i].group].push_back(i);
  for (auto& [g, idx] : groups) {
    if (dataset) std::sort(idx.begin(), idx.end(), [&](int x, int y) { return views[x].angle_deg < views[y].angle_deg; });
    for (std::size_t i = 0; i < idx.size(); ++i)
      for (std::size_t j = i + 1; j < idx.size(); ++j) {
        const bool take = rule == "consecutive" ? j == i + 1
                          : rule == "from-first" ? i == 0
                                                 : rotationBetween(views[idx[i]], views[idx[j]], dataset) <= within;
        if (take) pairs.emplace_back(idx[i], idx[j]);
      }
  }
  if (pairs.empty()) throw Error(a.input + ": no view pairs under --pairs " + a.pairs);

  // Detect once per view and detector.
  Progress detect("detect", views.size(), !a.json);
  for (auto& v : views) {
    Cloud c = loadCloud(v.file);
    if (!a.no_filter) c = filterCloud(c, FilterOptions());
    v.set = PointSet::fromCloud(c);
    v.res = cloudResolution(v.set);
    for (Detector d : detectors) {
      const auto t0 = std::chrono::steady_clock::now();
      v.kp[d] = detectKeypoints(d, v.set, v.res);
      v.ms[d] = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    }
    detect.advance();
  }
  detect.finish();

  fs::create_directories(a.out);
  std::ostringstream csv;
  csv << "detector,group,model_view,scene_view,rotation_deg,eps_res,eps_m,model_keypoints,scene_keypoints,visible,"
         "absolute,relative,icp_rms_m\n";
  struct Acc { std::vector<double> abs, rel; int n = 0; std::map<int, std::pair<double, int>> by_rot; };
  std::map<Detector, Acc> acc;
  for (Detector d : detectors) acc[d] = {std::vector<double>(eps.size()), std::vector<double>(eps.size()), 0, {}};
  const std::size_t eps2 = static_cast<std::size_t>(std::min_element(eps.begin(), eps.end(), [](double x, double y) {
                                                      return std::abs(x - 2.0) < std::abs(y - 2.0);
                                                    }) - eps.begin());
  Progress prog("pairs", pairs.size(), !a.json);
  double icp_sum = 0;
  for (const auto& [m, s] : pairs) {
    const View &vm = views[m], &vs = views[s];
    Eigen::Matrix4d T = vs.view_from_common * vm.view_from_common.inverse();
    double icp_rms = std::nan("");
    if (a.icp) {
      const auto r = refineByIcp(vm.set, vs.set, T, 5 * vs.res);
      T = r.scene_from_model;
      icp_rms = r.rms_m;
      icp_sum += r.rms_m;
    }
    const double rot = rotationBetween(vm, vs, dataset);
    std::vector<double> eps_m;
    for (double e : eps) eps_m.push_back(e * vs.res);
    for (Detector d : detectors) {
      const auto r = keypointRepeatability(vm.kp.at(d), vs.kp.at(d), vs.set, vs.res, T, eps_m);
      Acc& A = acc[d];
      ++A.n;
      for (std::size_t e = 0; e < eps.size(); ++e) {
        A.abs[e] += r.absolute[e];
        A.rel[e] += r.relative[e];
        csv << detectorName(d) << ',' << vm.group << ',' << fs::path(vm.file).filename().string() << ','
            << fs::path(vs.file).filename().string() << ',' << rot << ',' << eps[e] << ',' << eps_m[e] << ','
            << r.model_keypoints << ',' << r.scene_keypoints << ',' << r.visible << ',' << r.absolute[e] << ','
            << r.relative[e] << ',' << icp_rms << "\n";
      }
      auto& bucket = A.by_rot[static_cast<int>(std::lround(rot))];
      bucket.first += r.relative[eps2];
      bucket.second += 1;
    }
    prog.advance();
  }
  prog.finish();
  writeFileDurably(a.out + "/repeatability.csv", csv.str());

  // Summary, JSON, charts.
  double mean_res = 0;
  for (const auto& v : views) mean_res += v.res / views.size();
  nlohmann::json j = {{"input", a.input}, {"views", views.size()}, {"pairs", pairs.size()},
                      {"resolution_mm", mean_res * 1000}, {"eps_res", eps}, {"icp", a.icp}};
  if (a.icp) j["icp_rms_mm"] = icp_sum / pairs.size() * 1000;
  std::ostringstream md;
  md << "# Keypoint repeatability\n\n" << views.size() << " views, " << pairs.size() << " pairs (" << a.pairs
     << "), mean resolution " << mean_res * 1000 << " mm" << (a.icp ? ", ground truth refined by ICP" : "") << ".\n\n";
  md << "| detector | mean keypoints | detection ms |";
  for (double e : eps) md << " rel@" << e << " |";
  md << "\n|---|---|---|";
  for (std::size_t e = 0; e < eps.size(); ++e) md << "---|";
  md << "\n";
  ui::LineChart abs_chart{"Absolute repeatability", "ε (× resolution)", "repeatable keypoints (mean per pair)", {}};
  ui::LineChart rel_chart{"Relative repeatability", "ε (× resolution)", "repeatable / visible", {}, 0.0, 1.0};
  ui::LineChart rot_chart{"Relative repeatability at ε = " + std::to_string(eps[eps2]).substr(0, 4) + " × resolution",
                          "rotation between views (°)", "repeatable / visible", {}, 0.0, 1.0};
  for (Detector d : detectors) {
    Acc& A = acc[d];
    double kp = 0, ms = 0;
    for (const auto& v : views) {
      kp += static_cast<double>(v.kp.at(d).size()) / views.size();
      ms += v.ms.at(d) / views.size();
    }
    ui::Series sa{detectorName(d), eps, {}}, sr{detectorName(d), eps, {}}, so{detectorName(d), {}, {}};
    for (std::size_t e = 0; e < eps.size(); ++e) {
      sa.y.push_back(A.abs[e] / A.n);
      sr.y.push_back(A.rel[e] / A.n);
    }
    for (const auto& [deg, b] : A.by_rot) {
      so.x.push_back(deg);
      so.y.push_back(b.first / b.second);
    }
    md << "| " << detectorName(d) << " | " << kp << " | " << ms << " |";
    for (double r : sr.y) md << ' ' << std::round(r * 1000) / 1000 << " |";
    md << "\n";
    j["detectors"][detectorName(d)] = {{"absolute", sa.y}, {"relative", sr.y}, {"keypoints", kp}, {"detection_ms", ms}};
    abs_chart.series.push_back(sa);
    rel_chart.series.push_back(sr);
    rot_chart.series.push_back(so);
  }
  md << "\nPlots: `absolute_vs_eps.png`, `relative_vs_eps.png`, `relative_vs_rotation.png`; every pair and ε in "
        "`repeatability.csv`.\n";
  writeFileDurably(a.out + "/summary.md", md.str());
  writeFileDurably(a.out + "/summary.json", j.dump(2) + "\n");
  ui::saveChartPng(abs_chart, a.out + "/absolute_vs_eps.png");
  ui::saveChartPng(rel_chart, a.out + "/relative_vs_eps.png");
  ui::saveChartPng(rot_chart, a.out + "/relative_vs_rotation.png");
  if (a.json) std::cout << j.dump(2) << "\n";
  else std::cout << md.str() << "Report: " << a.out << "\n";
  return 0;
}

}  // namespace

Command addRepeatabilityCommand(CLI::App& app) {
  auto a = std::make_shared<RepArgs>();
  auto* cmd = app.add_subcommand("repeatability", "Keypoint repeatability of several detectors against ε");
  cmd->add_option("input", a->input, "A calibrated keyturn dataset, or a pose list file (docs/repeatability.md)")->required();
  cmd->add_option("--detectors", a->detectors, "Comma list: iss, harris3d, sift3d, uniform")->capture_default_str();
  cmd->add_option("--eps", a->eps, "ε as START:STOP:STEP or a list, in multiples of the resolution")->capture_default_str();
  cmd->add_option("--pairs", a->pairs, "consecutive, from-first or all-within:DEG")->capture_default_str();
  cmd->add_flag("--icp", a->icp, "Refine each pair's ground truth by ICP (residual reported)");
  cmd->add_flag("--no-filter", a->no_filter, "Use the views as they are");
  cmd->add_option("--out,-o", a->out, "Report folder (CSV, Markdown, JSON, PNG plots)")->required();
  cmd->add_flag("--json", a->json, "Print the summary as JSON");
  return {cmd, [a] { return runRepeatability(*a); }};
}

}  // namespace keyturn::app
