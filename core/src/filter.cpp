#include "keyturn/core/filter.h"

#include <Eigen/Geometry>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/sample_consensus/ransac.h>
#include <pcl/sample_consensus/sac_model_plane.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <string>
#include <unordered_map>
#include <utility>

#include "keyturn/core/median.h"
#include "keyturn/core/nearest_neighbours.h"
#include "keyturn/core/radius_search.h"
#include "pcl_points.h"
#include "quiet_pcl.h"
#include "voxel_key.h"

namespace keyturn {
namespace {

const Eigen::Vector3f kNaN = Eigen::Vector3f::Constant(std::nanf(""));

}  // namespace

void cropRange(Cloud& cloud, float min_range, float max_range) {
  for (auto& p : cloud.points) {
    if (!Cloud::isValid(p)) continue;
    const float r = p.norm();
    if ((min_range > 0 && r < min_range) || (max_range > 0 && r > max_range)) p = kNaN;
  }
}

void cropBox(Cloud& cloud, const Eigen::Vector3f& box_min, const Eigen::Vector3f& box_max) {
  for (auto& p : cloud.points)
    if (Cloud::isValid(p) && ((p.array() < box_min.array()).any() || (p.array() > box_max.array()).any()))
      p = kNaN;
}

std::size_t removeJumpEdges(Cloud& cloud, float angle_deg) {
  if (!cloud.organized()) return 0;
  const int w = static_cast<int>(cloud.width), h = static_cast<int>(cloud.height);
  // A mixed pixel lies between a foreground and a background surface along its
  // own ray: it has a neighbour nearly straight in front of it AND one nearly
  // straight behind it. The true edge pixels of either surface have only one
  // such neighbour and are kept, so a real surface is never cut back.
  const float cos_limit = std::cos(angle_deg * static_cast<float>(M_PI) / 180.0f);
  std::vector<char> remove(cloud.points.size(), 0);
  for (int v = 0; v < h; ++v) {
    for (int u = 0; u < w; ++u) {
      const std::size_t i = static_cast<std::size_t>(v) * w + u;
      const Eigen::Vector3f& p = cloud.points[i];
      if (!Cloud::isValid(p)) continue;
      const Eigen::Vector3f ray = p.normalized();
      bool nearer = false, farther = false;
      for (int dv = -1; dv <= 1; ++dv) {
        for (int du = -1; du <= 1; ++du) {
          const int uu = u + du, vv = v + dv;
          if ((du == 0 && dv == 0) || uu < 0 || vv < 0 || uu >= w || vv >= h) continue;
          const Eigen::Vector3f& q = cloud.points[static_cast<std::size_t>(vv) * w + uu];
          if (!Cloud::isValid(q)) continue;
          const Eigen::Vector3f d = q - p;
          const float along = ray.dot(d);
          if (std::abs(along) > cos_limit * d.norm()) (along < 0 ? nearer : farther) = true;
        }
      }
      remove[i] = nearer && farther;
    }
  }
  std::size_t n = 0;
  for (std::size_t i = 0; i < remove.size(); ++i)
    if (remove[i]) {
      cloud.points[i] = kNaN;
      ++n;
    }
  return n;
}

namespace {

// Spread of a set of 2D coordinates: the area between the 5th and 95th percentile in each axis.
double footprintArea(std::vector<float> u, std::vector<float> v) {
  if (u.size() < 2) return 0.0;
  auto span = [](std::vector<float>& x) {
    const std::size_t lo = x.size() / 20, hi = x.size() - 1 - x.size() / 20;
    std::nth_element(x.begin(), x.begin() + lo, x.end());
    const float a = x[lo];
    std::nth_element(x.begin(), x.begin() + hi, x.end());
    return static_cast<double>(x[hi] - a);
  };
  return span(u) * span(v);
}

std::string percent(std::size_t part, std::size_t whole) {
  return std::to_string(whole ? static_cast<int>(std::lround(100.0 * part / whole)) : 0) + "%";
}

// PCL's plane model with its inlier count in rows: RANSAC scores every hypothesis on every sampled
// point (200 × 5,000 on a view whose best plane holds a quarter of it: 47 % of such a real crop's
// chain in PCL's scalar loop). The hypotheses, their order and the fit stay PCL's; the count is the
// same (countPlaneInliers, tested against PCL's).
class RowCountedPlaneModel final : public pcl::SampleConsensusModelPlane<pcl::PointXYZ> {
 public:
  explicit RowCountedPlaneModel(const pcl::PointCloud<pcl::PointXYZ>::ConstPtr& cloud)
      : pcl::SampleConsensusModelPlane<pcl::PointXYZ>(cloud, false) {  // fixed seed: same cloud, same plane
    x_.reserve(cloud->size()), y_.reserve(cloud->size()), z_.reserve(cloud->size());
    for (const auto& p : *cloud) x_.push_back(p.x), y_.push_back(p.y), z_.push_back(p.z);
  }
  std::size_t countWithinDistance(const Eigen::VectorXf& model, const double threshold) const override {
    if (!isModelValid(model) || indices_->size() != x_.size()) return SampleConsensusModelPlane::countWithinDistance(model, threshold);
    return detail::countPlaneInliers(x_, y_, z_, model.head<4>(), threshold);
  }

 private:
  std::vector<float> x_, y_, z_;
};

}  // namespace

std::size_t detail::countPlaneInliers(const std::vector<float>& x, const std::vector<float>& y,
                                      const std::vector<float>& z, const Eigen::Vector4f& plane, double threshold) {
  // PCL's countWithinDistanceStandard: |plane · (x, y, z, 1)| < threshold, the dot product summed as
  // Eigen's SSE reduction of a 4-vector sums it, (a0 + a2) + (a1 + a3), the compare in double.
  const float a = plane[0], b = plane[1], c = plane[2], d = plane[3];
  std::size_t n = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const float v = (a * x[i] + c * z[i]) + (b * y[i] + d * 1.0f);
    n += static_cast<double>(std::abs(v)) < threshold ? 1 : 0;
  }
  return n;
}

bool removeDominantPlane(Cloud& cloud, const FilterOptions& options, Eigen::Vector4f* plane,
                         std::string* decision, float* removed_band) {
  auto say = [&](const std::string& why) {
    if (decision) *decision = why;
    return false;
  };
  std::vector<int> index;
  auto pts = detail::toPcl(cloud, &index);  // valid points, with the cloud index of each
  if (pts->size() < 10) return say("too few points for a plane");
  detail::quietPcl();  // "Not enough inliers found to optimize model coefficients" on scattered points
  // RANSAC scores its hypotheses on an even subsample (a full 640 x 480 frame has
  // 300k points; a plane needs far fewer to be found), then every point is labelled.
  pcl::PointCloud<pcl::PointXYZ>::Ptr sample = pts;
  const std::size_t cap = static_cast<std::size_t>(std::max(1000, options.plane_max_samples));
  if (pts->size() > cap) {
    sample.reset(new pcl::PointCloud<pcl::PointXYZ>);
    const double step = static_cast<double>(pts->size()) / static_cast<double>(cap);
    for (std::size_t k = 0; k < cap; ++k) sample->push_back((*pts)[static_cast<std::size_t>(k * step)]);
  }
  // RANSAC, then a least-squares fit to its inliers: what pcl::SACSegmentation (with optimised
  // coefficients) does, called from libpcl_sample_consensus directly, since libpcl_segmentation
  // would load PCL's features library at every start of the tool.
  pcl::SampleConsensusModelPlane<pcl::PointXYZ>::Ptr model(new RowCountedPlaneModel(sample));
  pcl::RandomSampleConsensus<pcl::PointXYZ> ransac(model, options.plane_distance);
  ransac.setMaxIterations(options.plane_iterations);
  if (!ransac.computeModel(0)) return say("no plane found");
  pcl::Indices inliers;
  ransac.getInliers(inliers);
  Eigen::VectorXf coeff, refined;
  ransac.getModelCoefficients(coeff);
  model->optimizeModelCoefficients(inliers, coeff, refined);
  if (refined.size() != 4) return say("no plane found");
  Eigen::Vector4f pl = refined.head<4>();
  pl /= pl.head<3>().norm();
  if (pl[3] < 0) pl = -pl;  // the camera (origin) on the positive side

  // Label every point: on the plane, in front of it (camera side) or behind it.
  const float band = options.plane_distance;
  float fine_band = band;  // plane_band_sigmas: the frame's own noise band (regrowBand uses it)
  if (options.plane_band_sigmas > 0.f && !inliers.empty()) {
    std::vector<float> d;
    d.reserve(inliers.size());
    for (const auto i : inliers) d.push_back(std::abs(pl.head<3>().dot((*sample)[i].getVector3fMap()) + pl[3]));
    const float sigma = 1.4826f * upperMedian(std::move(d));
    fine_band = std::clamp(options.plane_band_sigmas * sigma, std::min(options.plane_min_band, options.plane_distance),
                           options.plane_distance);
  }
  std::size_t on = 0, front = 0, behind = 0;
  std::vector<signed char> side(index.size());
  for (std::size_t k = 0; k < index.size(); ++k) {
    const float d = pl.head<3>().dot(cloud.points[index[k]]) + pl[3];
    side[k] = d >= band ? 1 : (d <= -band ? -1 : 0);
    (side[k] > 0 ? front : side[k] < 0 ? behind : on)++;
  }
  const std::string found = "plane with " + percent(on, index.size()) + " of the points, " +
                            std::to_string(front) + " in front of it, " + std::to_string(behind) + " behind";
  if (on < options.plane_min_fraction * static_cast<float>(index.size()))
    return say("largest plane holds " + percent(on, index.size()) + " of the points (< " +
               percent(static_cast<std::size_t>(options.plane_min_fraction * 1000), 1000) + "): kept");
  // The support rule. An object standing on a support lies on the camera's side of it;
  // the rest of an object lies behind any of its own visible faces.
  if (front < static_cast<std::size_t>(std::max(1, options.support_min_points)) || front < behind)
    return say(found + ": not a support (the rest lies behind it: a face of the object), kept");
  // A support spreads at least as wide as what stands on it; a plate's floor does not.
  const Eigen::Vector3f n = pl.head<3>();
  const Eigen::Vector3f a = (std::abs(n.x()) < 0.9f ? Eigen::Vector3f::UnitX() : Eigen::Vector3f::UnitY()).cross(n).normalized();
  const Eigen::Vector3f b = n.cross(a);
  std::vector<float> pu, pv, ou, ov;
  for (std::size_t k = 0; k < index.size(); ++k) {
    if (side[k] < 0) continue;
    const Eigen::Vector3f& p = cloud.points[index[k]];
    (side[k] == 0 ? pu : ou).push_back(a.dot(p));
    (side[k] == 0 ? pv : ov).push_back(b.dot(p));
  }
  const double plane_area = footprintArea(pu, pv), object_area = footprintArea(ou, ov);
  if (plane_area < object_area)
    return say(found + ": not a support (narrower than what lies in front of it), kept");
  // Everything within the band or behind the plane (under the table) goes.
  for (std::size_t k = 0; k < index.size(); ++k)
    if (side[k] <= 0) cloud.points[index[k]] = kNaN;
  if (plane) *plane = pl;
  if (removed_band) *removed_band = fine_band;
  if (decision) *decision = found + ": a support, removed with what lies behind it";
  return true;
}

void keepLargestCluster(Cloud& cloud, float tolerance) {
  // Connected components of the tolerance-ball graph (points closer than `tolerance`
  // are joined), exactly, without a radius search per point: points share a voxel of
  // side t/sqrt(3) only when closer than t, so each voxel is one piece from the start;
  // neighbouring voxels (up to 2 cells away) are joined, by union-find, as soon as one
  // pair of their points is closer than t.
  std::vector<int> index;
  for (std::size_t i = 0; i < cloud.points.size(); ++i)
    if (Cloud::isValid(cloud.points[i])) index.push_back(static_cast<int>(i));
  if (index.size() < 2 || !(tolerance > 0.f)) return;
  const double side = tolerance / std::sqrt(3.0) * 0.999;
  // Bounded before the cast (past int is undefined behaviour): far points share the edge cells and
  // the distance test below decides.
  auto axisCell = [&](float x) { return static_cast<int>(std::clamp(std::floor(x / side), -1e9, 1e9)); };
  auto cellOf = [&](const Eigen::Vector3f& p) { return Eigen::Vector3i(axisCell(p.x()), axisCell(p.y()), axisCell(p.z())); };
  auto key = [](const Eigen::Vector3i& c) { return detail::voxelKey(c.x(), c.y(), c.z()); };
  std::vector<std::pair<std::uint64_t, int>> order(index.size());
  for (std::size_t k = 0; k < index.size(); ++k) order[k] = {key(cellOf(cloud.points[index[k]])), index[k]};
  std::sort(order.begin(), order.end());
  struct Voxel { int begin, end; Eigen::Vector3i cell; };
  std::vector<Voxel> voxels;
  for (std::size_t b = 0; b < order.size();) {
    std::size_t e = b;
    while (e < order.size() && order[e].first == order[b].first) ++e;
    voxels.push_back({static_cast<int>(b), static_cast<int>(e), cellOf(cloud.points[order[b].second])});
    b = e;
  }
  // Each voxel's tight box: two voxels whose boxes lie t or farther apart hold no joined pair.
  std::vector<Eigen::AlignedBox3f> box(voxels.size());
  for (std::size_t v = 0; v < voxels.size(); ++v)
    for (int i = voxels[v].begin; i < voxels[v].end; ++i) box[v].extend(cloud.points[order[i].second]);
  // Voxels are in key order, x fastest: a row of voxels along x (one y, z) is one run of them.
  std::unordered_map<std::uint64_t, std::pair<int, int>> row_of;  // (y, z) → [first, end) voxel
  for (int v = 0; v < static_cast<int>(voxels.size()); ++v) {
    auto& run = row_of.try_emplace(key(Eigen::Vector3i(0, voxels[v].cell.y(), voxels[v].cell.z())), v, v).first->second;
    run.second = v + 1;
  }
  std::vector<int> parent(voxels.size());
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  const float t2 = tolerance * tolerance;
  const float box_t2 = t2 * 1.0001f;  // a margin for the rounding of the two sums
  auto join = [&](int v, int w) {
    const int ra = find(v), rb = find(w);
    if (ra == rb || box[v].squaredExteriorDistance(box[w]) > box_t2) return;
    const Voxel& a = voxels[v];
    const Voxel& b = voxels[w];
    for (int i = a.begin; i < a.end; ++i)
      for (int j = b.begin; j < b.end; ++j)
        if ((cloud.points[order[i].second] - cloud.points[order[j].second]).squaredNorm() < t2) {
          parent[ra] = rb;
          return;
        }
  };
  // Two passes: the touching cells (nearly always joined by their first pair), then those up to 2
  // cells away, most of them already joined by then. One hash lookup per row of cells, not per cell
  // (124 per voxel before): with the boxes, 6.5 → 2.6 ms on a real 20,792-point crop.
  for (int reach : {1, 2})
    for (int v = 0; v < static_cast<int>(voxels.size()); ++v) {
      const Eigen::Vector3i& c = voxels[v].cell;
      for (int dy = -reach; dy <= reach; ++dy)
        for (int dz = -reach; dz <= reach; ++dz) {
          const auto row = row_of.find(key(Eigen::Vector3i(0, c.y() + dy, c.z() + dz)));
          if (row == row_of.end()) continue;
          for (int w = row->second.first; w < row->second.second; ++w) {
            const Eigen::Vector3i& o = voxels[w].cell;
            if (w <= v || o.y() != c.y() + dy || o.z() != c.z() + dz || std::abs(o.x() - c.x()) > reach) continue;
            join(v, w);
          }
        }
    }
  std::vector<std::size_t> size(voxels.size(), 0);
  for (std::size_t v = 0; v < voxels.size(); ++v) size[find(static_cast<int>(v))] += voxels[v].end - voxels[v].begin;
  // The largest component; a tie goes to the one holding the lowest point index.
  int best = -1;
  std::vector<int> lowest(voxels.size(), std::numeric_limits<int>::max());
  for (std::size_t v = 0; v < voxels.size(); ++v) {
    const int root = find(static_cast<int>(v));
    for (int i = voxels[v].begin; i < voxels[v].end; ++i) lowest[root] = std::min(lowest[root], order[i].second);
  }
  for (std::size_t v = 0; v < voxels.size(); ++v) {
    const int root = find(static_cast<int>(v));
    if (best < 0 || size[root] > size[best] || (size[root] == size[best] && lowest[root] < lowest[best])) best = root;
  }
  const Eigen::Vector3f nan = kNaN;
  for (std::size_t v = 0; v < voxels.size(); ++v)
    if (find(static_cast<int>(v)) != best)
      for (int i = voxels[v].begin; i < voxels[v].end; ++i) cloud.points[order[i].second] = nan;
}

void removeStatisticalOutliers(Cloud& cloud, int k, float std_mul) {
  std::vector<int> index;
  std::vector<Eigen::Vector3f> valid;
  for (std::size_t i = 0; i < cloud.points.size(); ++i) {
    if (!Cloud::isValid(cloud.points[i])) continue;
    valid.push_back(cloud.points[i]);
    index.push_back(static_cast<int>(i));
  }
  const std::size_t n = index.size();
  if (k < 1 || n <= static_cast<std::size_t>(k)) return;
  // The k + 1 nearest of each point (it finds itself first), exactly the squared distances PCL's
  // k-d tree gives (nearest_neighbours.h), all at once from a hash grid: 4–8 × faster than the
  // tree searched in one batch (docs/benchmarks.md).
  const std::size_t searched = static_cast<std::size_t>(k) + 1;
  const std::vector<float> nn_sq = nearestSquaredDistances(valid, static_cast<int>(searched));
  // From here PCL's arithmetic, step by step (float means, double sums), so the same points go.
  std::vector<float> mean_distance(n);
  for (std::size_t q = 0; q < n; ++q) {
    double sum = 0.0;
    for (std::size_t j = 1; j < searched; ++j) sum += std::sqrt(nn_sq[q * searched + j]);
    mean_distance[q] = static_cast<float>(sum / k);
  }
  double sum = 0, sq_sum = 0;
  for (const float d : mean_distance) {
    sum += d;
    sq_sum += d * d;
  }
  const double count = static_cast<double>(n);
  const double mean = sum / count;
  const double stddev = std::sqrt((sq_sum - sum * sum / count) / (count - 1));
  const double threshold = mean + std_mul * stddev;
  for (std::size_t q = 0; q < n; ++q)
    if (mean_distance[q] > threshold) cloud.points[index[q]] = kNaN;
}

const char* inputKindName(InputKind kind) {
  switch (kind) {
    case InputKind::Frame: return "frame";
    case InputKind::MaskedFrame: return "masked-frame";
    default: return "segmented-cloud";
  }
}

InputKind classifyInput(const Cloud& cloud) {
  if (!cloud.organized()) return InputKind::SegmentedCloud;
  const double valid = static_cast<double>(cloud.validCount()) / static_cast<double>(cloud.size());
  return valid < kMaskedFrameMaxValidFraction ? InputKind::MaskedFrame : InputKind::Frame;
}

bool FilterReport::anyFlagged() const {
  return std::any_of(steps.begin(), steps.end(), [](const FilterStep& s) { return s.flagged; });
}

std::string FilterReport::flaggedSummary() const {
  std::string out;
  for (const auto& s : steps) {
    if (!s.flagged) continue;
    if (!out.empty()) out += "; ";
    out += s.name + " removed " + percent(s.removed(), s.before) + " (" + std::to_string(s.removed()) + " of " +
           std::to_string(s.before) + ")";
  }
  return out;
}

namespace {

// The points of `before` within [band, plane_distance) above the support that connect to the kept
// object (`cloud`) through points closer than `tolerance` to each other, put back. The support's
// decision and the object's cluster are made with the fixed band (a frame's far table is noisier
// than its near table, and a noise band alone leaves it in pieces); only the object's foot returns.
std::size_t regrowBand(Cloud& cloud, const Cloud& before, const Eigen::Vector4f& plane, float band, float top,
                       float tolerance) {
  const double inv = 1.0 / tolerance;
  auto key = [&](const Eigen::Vector3f& p, int dx, int dy, int dz) {
    return detail::voxelKey(detail::voxelCell(p.x(), inv) + dx, detail::voxelCell(p.y(), inv) + dy,
                            detail::voxelCell(p.z(), inv) + dz);
  };
  std::unordered_map<std::uint64_t, std::vector<int>> candidates;
  for (std::size_t i = 0; i < before.points.size(); ++i) {
    const Eigen::Vector3f& p = before.points[i];
    if (!Cloud::isValid(p) || Cloud::isValid(cloud.points[i])) continue;
    const float d = plane.head<3>().dot(p) + plane[3];
    if (d >= band && d < top) candidates[key(p, 0, 0, 0)].push_back(int(i));
  }
  std::vector<int> queue;
  for (std::size_t i = 0; i < cloud.points.size(); ++i)
    if (Cloud::isValid(cloud.points[i])) queue.push_back(int(i));
  std::size_t added = 0;
  const float t2 = tolerance * tolerance;
  while (!queue.empty()) {
    const Eigen::Vector3f p = cloud.points[queue.back()];
    queue.pop_back();
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          auto it = candidates.find(key(p, dx, dy, dz));
          if (it == candidates.end()) continue;
          auto& list = it->second;
          for (std::size_t k = 0; k < list.size();) {
            if ((before.points[list[k]] - p).squaredNorm() <= t2) {
              cloud.points[list[k]] = before.points[list[k]];
              queue.push_back(list[k]);
              ++added;
              list[k] = list.back();
              list.pop_back();
            } else {
              ++k;
            }
          }
        }
  }
  return added;
}

}  // namespace

Cloud filterCloud(const Cloud& input, const FilterOptions& o, FilterReport* report,
                  const WorkingResolutionOptions* working, WorkingResolutionReport* working_report,
                  Cloud* before_working) {
  Cloud cloud = input;
  FilterReport r;
  // Points beyond kMaxCoordinate are no measurement (float squared distances between them overflow,
  // and the voxel steps' means with them): invalid, as a loader reads them.
  for (auto& p : cloud.points)
    if (Cloud::isValid(p) && p.cwiseAbs().maxCoeff() > kMaxCoordinate) {
      p = kNaN;
      ++r.too_far;
    }
  r.kind = classifyInput(input);
  r.input_valid = cloud.validCount();
  const bool camera_frame = r.kind != InputKind::SegmentedCloud;
  std::size_t count = r.input_valid;
  // Runs one step and records it. On a frame with a support, the plane and cluster
  // steps segment the object out of a scene: removing most of the frame is their
  // job. Any other step that removes more than half of what it was given is flagged.
  auto step = [&](const char* name, bool wanted, const std::string& skip_note, auto&& run) {
    FilterStep s;
    s.name = name;
    s.before = count;
    s.applied = wanted;
    if (wanted) run(s);
    else s.note = skip_note;
    s.after = count = cloud.validCount();
    const bool segmenting =
        s.name == "working-resolution" || (r.plane_found && (s.name == "support-plane" || s.name == "cluster"));
    s.flagged = s.applied && !segmenting && s.before > 0 && 2 * s.removed() > s.before;
    r.steps.push_back(std::move(s));
  };
  step("crop", camera_frame && (o.crop_range || o.crop_box), camera_frame ? "off" : "not a camera frame", [&](FilterStep&) {
    if (o.crop_range) cropRange(cloud, o.min_range, o.max_range);
    if (o.crop_box) cropBox(cloud, o.box_min, o.box_max);
  });
  r.after_crop = count;
  step("jump-edges", cloud.organized() && o.jump_edge, cloud.organized() ? "off" : "not organized",
       [&](FilterStep&) { removeJumpEdges(cloud, o.jump_edge_angle_deg); });
  r.after_jump_edge = count;
  const Cloud before_plane = o.plane_band_sigmas > 0.f ? cloud : Cloud();
  step("support-plane", o.remove_plane, "off", [&](FilterStep& s) {
    r.plane_found = removeDominantPlane(cloud, o, &r.plane, &s.note, &r.plane_band);
  });
  r.after_plane = count;
  step("cluster", o.largest_cluster, "off", [&](FilterStep&) { keepLargestCluster(cloud, o.cluster_tolerance); });
  if (r.plane_found && o.plane_band_sigmas > 0.f && r.plane_band < o.plane_distance)
    step("support-band", true, "", [&](FilterStep& s) {
      const std::size_t added = regrowBand(cloud, before_plane, r.plane, r.plane_band, o.plane_distance, o.plane_regrow);
      s.note = std::to_string(added) + " points of the object's foot within " +
               std::to_string(int(std::lround(r.plane_band * 1000))) + "–" +
               std::to_string(int(std::lround(o.plane_distance * 1000))) + " mm of the support put back";
    });
  r.after_cluster = count;
  if (working)
    step("working-resolution", working->enabled, "off", [&](FilterStep&) {
      if (before_working) *before_working = cloud;
      WorkingResolutionReport w;
      subsampleToWorkingResolution(cloud, *working, &w);
      if (working_report) *working_report = w;
    });
  step("outliers", o.outlier_removal, "off",
       [&](FilterStep&) { removeStatisticalOutliers(cloud, o.sor_k, o.sor_std_mul); });
  r.after_outliers = count;
  if (report) *report = std::move(r);
  return cloud;
}

}  // namespace keyturn
