// The repeatability study: pairs, the overlap check, native and equal-K detection,
// scores per pair and their means per detector.
#include "keyturn/studies/repeatability_study.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>

#include "keyturn/core/cloud_io.h"
#include "keyturn/core/error.h"
#include "keyturn/core/filter.h"
#include "keyturn/core/descriptor.h"
#include "keyturn/core/keypoint_placement.h"
#include "keyturn/core/keypoint_refinement.h"
#include "keyturn/core/radius_search.h"
#include "keyturn/core/string_format.h"

namespace keyturn {

PairRule parsePairRule(const std::string& text) {
  PairRule r;
  if (text == "consecutive") return r;
  if (text == "from-first") {
    r.kind = PairRule::Kind::FromFirst;
    return r;
  }
  if (text.rfind("all-within:", 0) == 0) {
    const std::string deg = text.substr(11);
    char* end = nullptr;
    const double v = std::strtod(deg.c_str(), &end);
    if (deg.empty() || *end != '\0' || !std::isfinite(v) || v < 0)
      throw Error("pair rule '" + text + "': all-within needs degrees (0 or more)");
    r.kind = PairRule::Kind::AllWithin;
    r.within_deg = v;
    return r;
  }
  throw Error("pair rule '" + text + "': expected consecutive, from-first or all-within:DEG");
}

std::string pairRuleName(const PairRule& r) {
  switch (r.kind) {
    case PairRule::Kind::Consecutive: return "consecutive";
    case PairRule::Kind::FromFirst: return "from-first";
    default: break;
  }
  char b[48];
  std::snprintf(b, sizeof b, "all-within:%g", r.within_deg);
  return b;
}

double rotationBetween(const StudyView& a, const StudyView& b) {
  if (std::isfinite(a.angle_deg) && std::isfinite(b.angle_deg)) {
    const double d = std::fmod(std::abs(a.angle_deg - b.angle_deg), 360.0);
    return d > 180 ? 360 - d : d;
  }
  const Eigen::Matrix3d r = (b.view_from_common * a.view_from_common.inverse()).topLeftCorner<3, 3>();
  return Eigen::AngleAxisd(r).angle() * 180 / M_PI;
}

std::vector<std::pair<int, int>> selectPairs(const std::vector<StudyView>& views, const PairRule& rule) {
  std::map<std::string, std::vector<int>> groups;
  for (int i = 0; i < static_cast<int>(views.size()); ++i) groups[views[i].group].push_back(i);
  std::vector<std::pair<int, int>> pairs;
  for (auto& [g, idx] : groups) {
    // By angle, views without one (posed by matrices) after those with one: a strict weak order.
    std::stable_sort(idx.begin(), idx.end(), [&](int x, int y) {
      const double ax = views[x].angle_deg, ay = views[y].angle_deg;
      if (std::isfinite(ax) != std::isfinite(ay)) return std::isfinite(ax);
      return std::isfinite(ax) && ax < ay;
    });
    for (std::size_t i = 0; i < idx.size(); ++i)
      for (std::size_t j = i + 1; j < idx.size(); ++j) {
        const bool take = rule.kind == PairRule::Kind::Consecutive ? j == i + 1
                          : rule.kind == PairRule::Kind::FromFirst
                              ? i == 0
                              : rotationBetween(views[idx[i]], views[idx[j]]) <= rule.within_deg;
        if (take) pairs.emplace_back(idx[i], idx[j]);
      }
  }
  return pairs;
}

namespace {

struct Loaded {
  PointSet set;
  double res = 0;
  PointSet working_set;  // the view at describe's working resolution (iss-chain only)
  double working_res = 0;
  bool subsampled = false;  // describe keeps (and places keypoints on) the measured view only then
  int budget = 0;
  std::map<Detector, std::vector<Eigen::Vector3f>> native, equal;
  std::map<Detector, double> ms;
};

Eigen::Matrix4d sceneFromModel(const StudyView& m, const StudyView& s, bool inverted) {
  return inverted ? Eigen::Matrix4d(s.view_from_common.inverse() * m.view_from_common)
                  : Eigen::Matrix4d(s.view_from_common * m.view_from_common.inverse());
}

double meanOverlap(const std::vector<StudyView>& views, const std::vector<Loaded>& data,
                   const std::vector<std::pair<int, int>>& pairs, double k, bool inverted, std::vector<double>* each) {
  double sum = 0;
  for (const auto& [m, s] : pairs) {
    const double f = overlapFraction(data[m].set, data[s].set, sceneFromModel(views[m], views[s], inverted), k * data[s].res);
    if (each) each->push_back(f);
    sum += f;
  }
  return pairs.empty() ? 0 : sum / pairs.size();
}

std::string percent(double f) {
  char b[32];
  std::snprintf(b, sizeof b, "%.0f %%", 100 * f);
  return b;
}

}  // namespace

Study runRepeatabilityStudy(std::vector<StudyView> views, const StudyOptions& o, const StudyProgress& progress) {
  if (views.size() < 2) throw Error("repeatability needs at least 2 views");
  if (o.detectors.empty() || o.eps_res.empty()) throw Error("repeatability needs a detector and a value of ε");
  for (double e : o.eps_res)
    if (!(e > 0) || !std::isfinite(e)) {
      std::string text;
      appendFormat(text, "ε %g: must be a positive multiple of the resolution", e);
      throw Error(text);
    }
  Study st;
  st.options = o;
  const auto pairs = selectPairs(views, o.pairs);
  if (pairs.empty()) throw Error("no view pairs under the pair rule " + pairRuleName(o.pairs));

  std::vector<Loaded> data(views.size());
  progress.begin("load", views.size());
  for (std::size_t i = 0; i < views.size(); ++i) {
    Cloud c = loadCloud(views[i].file, o.depth);
    if (o.filter) c = filterCloud(c, FilterOptions());
    data[i].set = PointSet::fromCloud(c);
    if (data[i].set.size() < 2) throw Error(views[i].file + ": fewer than 2 points left to detect keypoints on");
    data[i].res = cloudResolution(data[i].set);
    if (std::any_of(o.detectors.begin(), o.detectors.end(), isChainDetector)) {
      // As describe prepares a view (prepareView): the filtered view at the working resolution,
      // its radii in multiples of the working spacing at least.
      WorkingResolutionReport w;
      subsampleToWorkingResolution(c, o.working, &w);
      data[i].working_set = PointSet::fromCloud(c);
      if (w.off_pixel_rays) data[i].working_set.forgetPixels();
      data[i].working_res = std::max(cloudResolution(data[i].working_set), w.subsampled ? w.spacing : 0.0);
      data[i].subsampled = w.subsampled;
    }
    st.mean_resolution_m += data[i].res / views.size();
    progress.step();
  }
  progress.end();

  // The poses must make the views overlap, or every score is a meaningless 0.
  std::vector<double> overlap;
  st.mean_overlap = meanOverlap(views, data, pairs, o.overlap_radius_res, false, &overlap);
  const auto bare = std::count_if(overlap.begin(), overlap.end(), [&](double f) { return f < o.overlap_min; });
  if (2 * bare > static_cast<long>(pairs.size())) {
    st.mean_overlap_inverted = meanOverlap(views, data, pairs, o.overlap_radius_res, true, nullptr);
    const bool inverse_overlaps = st.mean_overlap_inverted >= 2 * o.overlap_min;
    const std::string hint = inverse_overlaps ? " — inverted? the inverse gives " + percent(st.mean_overlap_inverted)
                                              : " — nor does their inverse (" + percent(st.mean_overlap_inverted) +
                                                    "): check the pose format and the units (metres)";
    if (!o.force)
      throw NoOverlapError("poses give no overlap between views (" + std::to_string(bare) + " of " +
                               std::to_string(pairs.size()) + " pairs under " + percent(o.overlap_min) + ")" + hint,
                           inverse_overlaps);
  }

  // describe's defaults, which iss-chain follows (its placement, and DescriptorOptions::iss's filled budget).
  const DescriptorOptions describe_defaults;
  DetectorOptions chain_detector = o.detector;
  chain_detector.iss.fill_budget = describe_defaults.iss.fill_budget;
  progress.begin("detect", views.size());
  for (auto& v : data) {
    // The budget K is ISS's native count unless given; ISS runs for it even when not compared.
    v.budget = o.keypoints > 0 ? o.keypoints : static_cast<int>(detectKeypoints(Detector::Iss, v.set, v.res, o.detector).size());
    for (Detector d : o.detectors) {
      const bool chain = isChainDetector(d);
      // The chain's keypoints as describe places them: iss-chain with describe's default placement,
      // iss-refined with --refine-keypoints, iss-nearest, iss-salient and iss-measured with
      // --keypoint-placement. "measured" detects on the measured points at the chain's scale; the
      // others detect on the working-resolution view, then place.
      KeypointPlacementOptions p = d == Detector::IssChain ? describe_defaults.placement : o.placement;
      if (d == Detector::IssNearest) p.placement = KeypointPlacement::Nearest;
      if (d == Detector::IssSalient) p.placement = KeypointPlacement::Salient;
      if (d == Detector::IssMeasured) p.placement = KeypointPlacement::Measured;
      const bool on_measured = chain && d != Detector::IssRefined && p.placement == KeypointPlacement::Measured;
      const PointSet& set = chain && !on_measured ? v.working_set : v.set;
      const double res = chain ? v.working_res : v.res;
      auto refined = [&](std::vector<Eigen::Vector3f> kp) {
        if (!chain || !v.subsampled || on_measured) return kp;
        if (d == Detector::IssRefined) {
          KeypointRefinementOptions r;
          r.enabled = true;
          return refineKeypointsOnMeasuredPoints(v.set, kp, v.working_res, o.detector.iss, r);
        }
        return placeKeypoints(v.set, kp, v.working_res, o.detector.iss, p);
      };
      const DetectorOptions& dopt = chain ? chain_detector : o.detector;
      const auto t0 = std::chrono::steady_clock::now();
      v.native[d] = refined(detectKeypoints(d, set, res, dopt));
      v.ms[d] = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      v.equal[d] = refined(detectKeypointsAtBudget(d, set, res, v.budget, dopt));
    }
    progress.step();
  }
  progress.end();

  st.eps_near_2 = static_cast<std::size_t>(std::min_element(o.eps_res.begin(), o.eps_res.end(), [](double x, double y) {
                                              return std::abs(x - 2.0) < std::abs(y - 2.0);
                                            }) - o.eps_res.begin());
  const std::size_t ne = o.eps_res.size();
  for (Detector d : o.detectors) {
    auto& S = st.detectors[d];
    S.absolute.assign(ne, 0);
    S.relative.assign(ne, 0);
    S.absolute_equal.assign(ne, 0);
    S.relative_equal.assign(ne, 0);
    for (const auto& v : data) {
      S.keypoints += static_cast<double>(v.native.at(d).size()) / data.size();
      S.equal_keypoints += static_cast<double>(v.equal.at(d).size()) / data.size();
      S.detection_ms += v.ms.at(d) / data.size();
    }
  }
  progress.begin("pairs", pairs.size());
  double icp_sum = 0;
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    const auto [m, s] = pairs[p];
    PairScore ps;
    ps.model = m;
    ps.scene = s;
    ps.overlap = overlap[p];
    ps.rotation_deg = rotationBetween(views[m], views[s]);
    Eigen::Matrix4d T = sceneFromModel(views[m], views[s], false);
    if (o.icp) {
      const auto r = refineByIcp(data[m].set, data[s].set, T, 5 * data[s].res);
      T = r.scene_from_model;
      ps.icp_rms_m = r.rms_m;
      icp_sum += r.rms_m;
    }
    std::vector<double> eps_m;
    for (double e : o.eps_res) eps_m.push_back(e * data[s].res);
    ps.eps_m = eps_m;
    const int rot = static_cast<int>(std::lround(ps.rotation_deg));
    for (Detector d : o.detectors) {
      auto& S = st.detectors[d];
      const auto rn = keypointRepeatability(data[m].native.at(d), data[s].native.at(d), data[s].set, data[s].res, T, eps_m);
      const auto rq = keypointRepeatability(data[m].equal.at(d), data[s].equal.at(d), data[s].set, data[s].res, T, eps_m);
      for (std::size_t e = 0; e < ne; ++e) {
        S.absolute[e] += rn.absolute[e] / static_cast<double>(pairs.size());
        S.relative[e] += rn.relative[e] / static_cast<double>(pairs.size());
        S.absolute_equal[e] += rq.absolute[e] / static_cast<double>(pairs.size());
        S.relative_equal[e] += rq.relative[e] / static_cast<double>(pairs.size());
      }
      auto& bn = S.relative_by_rotation[rot];
      bn.first += rn.relative[st.eps_near_2];
      ++bn.second;
      auto& bq = S.relative_equal_by_rotation[rot];
      bq.first += rq.relative[st.eps_near_2];
      ++bq.second;
      ps.native[d] = rn;
      ps.equal[d] = rq;
    }
    st.pairs.push_back(std::move(ps));
    progress.step();
  }
  progress.end();
  if (o.icp) st.mean_icp_rms_m = icp_sum / pairs.size();
  st.views = std::move(views);
  return st;
}

}  // namespace keyturn
