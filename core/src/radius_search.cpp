// Fixed-radius search. For organized ToF clouds the pixel grid already is a
// spatial index: a point q within r of p sees p's viewing ray at an angle of at
// most asin(r / (|p| - r)), so a pixel window of that angular half-width,
// measured with the smallest angle between adjacent rays, is exact.
#include "keyturn/core/radius_search.h"

#include <pcl/kdtree/kdtree_flann.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cmath>
#include <cstdint>
#include <limits>
#include <mutex>
#include <unordered_map>
#include <utility>

#include "keyturn/core/error.h"
#include "keyturn/core/nearest_neighbours.h"
#include "pcl_points.h"
#include "voxel_key.h"

namespace keyturn {

struct RadiusSearch::Impl {
  virtual ~Impl() = default;
  virtual void radius(int i, float r, std::vector<int>& out) const = 0;
  virtual float nearest(int i) const = 0;
  virtual bool grid() const = 0;
};

namespace {

class KdTreeSearch final : public RadiusSearch::Impl {
 public:
  explicit KdTreeSearch(const PointSet& set) : set_(set) {}
  void radius(int i, float r, std::vector<int>& out) const override {
    build();
    out.clear();
    pcl::Indices idx;
    std::vector<float> d2;
    tree_.radiusSearch((*cloud_)[i], r, idx, d2);
    const float r2 = r * r;
    for (std::size_t k = 0; k < idx.size(); ++k)
      if (d2[k] < r2) out.push_back(idx[k]);
    std::sort(out.begin(), out.end());
  }
  // Every point's nearest distance at once, on the first ask (the hash grid of nearest_neighbours.h:
  // the values of the k-d tree point by point, tested); the second nearest counting the point
  // itself is its nearest other point (0 for a twin, as the tree gives).
  float nearest(int i) const override {
    if (set_.size() < 2) return std::numeric_limits<float>::infinity();
    std::call_once(nearest_done_, [this] { nearest_d2_ = nearestSquaredDistances(set_.points, 2); });
    return std::sqrt(nearest_d2_[2 * static_cast<std::size_t>(i) + 1]);
  }
  bool grid() const override { return false; }

 private:
  // Built on the first radius query the cached table cannot serve: the chain reads every
  // neighbourhood from the table, so it never needs the tree.
  void build() const {
    std::call_once(built_, [this] {
      cloud_ = detail::toPcl(set_.points);
      if (!cloud_->empty()) tree_.setInputCloud(cloud_);
    });
  }
  const PointSet& set_;
  mutable std::once_flag built_;
  mutable pcl::PointCloud<pcl::PointXYZ>::Ptr cloud_;
  mutable pcl::KdTreeFLANN<pcl::PointXYZ> tree_;
  mutable std::once_flag nearest_done_;
  mutable std::vector<float> nearest_d2_;
};

class GridSearch final : public RadiusSearch::Impl {
 public:
  GridSearch(const PointSet& set, double min_angle) : set_(set), angle_(min_angle) {}

  void radius(int i, float r, std::vector<int>& out) const override {
    out.clear();
    const Eigen::Vector3f& p = set_.points[i];
    const float r2 = r * r;
    forWindow(i, halfWidth(p.norm(), r), [&](int j) {
      if ((set_.points[j] - p).squaredNorm() < r2) out.push_back(j);
    });
  }

  float nearest(int i) const override {
    const Eigen::Vector3f& p = set_.points[i];
    const int max_h = static_cast<int>(std::max(set_.width, set_.height));
    float best2 = std::numeric_limits<float>::infinity();
    // Grow the window until some neighbour appears, then make the window wide
    // enough that no closer point can hide outside it.
    for (int h = 1; h <= max_h && !std::isfinite(best2); h *= 2) scan(i, h, p, best2);
    if (!std::isfinite(best2)) return best2;
    scan(i, halfWidth(p.norm(), std::sqrt(best2)), p, best2);
    return std::sqrt(best2);
  }
  bool grid() const override { return true; }

 private:
  void scan(int i, int h, const Eigen::Vector3f& p, float& best2) const {
    forWindow(i, h, [&](int j) {
      if (j == i) return;
      best2 = std::min(best2, (set_.points[j] - p).squaredNorm());
    });
  }

  int halfWidth(float range, float r) const {
    const int max_h = static_cast<int>(std::max(set_.width, set_.height));
    if (range <= 2.0f * r) return max_h;  // too close to the camera for the bound: search all
    const double theta = std::asin(std::min(1.0, static_cast<double>(r) / (range - r)));
    return std::min(max_h, static_cast<int>(std::ceil(theta / angle_)));
  }

  template <typename F>
  void forWindow(int i, int h, F&& visit) const {
    const int w = static_cast<int>(set_.width), ht = static_cast<int>(set_.height);
    const int pix = set_.pixel[i];
    const int u0 = pix % w, v0 = pix / w;
    const int ua = std::max(0, u0 - h), ub = std::min(w - 1, u0 + h);
    const int va = std::max(0, v0 - h), vb = std::min(ht - 1, v0 + h);
    for (int v = va; v <= vb; ++v) {
      const int* row = set_.pixel_to_point.data() + static_cast<std::size_t>(v) * w;
      for (int u = ua; u <= ub; ++u)
        if (row[u] >= 0) visit(row[u]);
    }
  }

  const PointSet& set_;
  double angle_;  // smallest angle between the rays of adjacent pixels (radians)
};

double angleBetween(const Eigen::Vector3f& a, const Eigen::Vector3f& b) {
  const double c = static_cast<double>(a.normalized().dot(b.normalized()));
  return std::acos(std::clamp(c, -1.0, 1.0));
}

// Smallest angular pixel pitch (2nd percentile, with a 10% margin) measured from
// the rays of horizontally and vertically adjacent valid pixels. 0 when unknown.
double minimumRayAngle(const PointSet& set) {
  std::vector<double> angles;
  const int w = static_cast<int>(set.width), h = static_cast<int>(set.height);
  for (std::size_t k = 0; k < set.size(); ++k) {
    const int pix = set.pixel[k], u = pix % w, v = pix / w;
    if (u + 1 < w && set.pixel_to_point[pix + 1] >= 0)
      angles.push_back(angleBetween(set.points[k], set.points[set.pixel_to_point[pix + 1]]));
    if (v + 1 < h && set.pixel_to_point[pix + w] >= 0)
      angles.push_back(angleBetween(set.points[k], set.points[set.pixel_to_point[pix + w]]));
  }
  if (angles.size() < 8) return 0.0;
  const std::size_t q = angles.size() / 50;
  std::nth_element(angles.begin(), angles.begin() + q, angles.end());
  return 0.9 * angles[q];
}

}  // namespace

RadiusSearch::RadiusSearch(const PointSet& set) : set_(&set) {
  const double angle = set.organized() ? minimumRayAngle(set) : 0.0;
  if (angle > 1e-6) impl_ = std::make_unique<GridSearch>(set, angle);
  else impl_ = std::make_unique<KdTreeSearch>(set);
}

RadiusSearch::~RadiusSearch() = default;

std::unique_ptr<RadiusSearch> RadiusSearch::kdTree(const PointSet& set) {
  std::unique_ptr<RadiusSearch> s(new RadiusSearch());
  s->impl_ = std::make_unique<KdTreeSearch>(set);
  s->set_ = &set;
  return s;
}

void RadiusSearch::radius(int i, float r, std::vector<int>& out) const {
  // A radius of 0 (or NaN) holds no other point: i alone, as the contract promises. A cached
  // table's rows exist only once it was built (table_radius_ > 0).
  if (!(r > 0.f)) {
    out.assign(1, i);
    return;
  }
  if (r > table_radius_ || row_offset_.empty()) return impl_->radius(i, r, out);
  out.clear();
  const float r2 = r * r;
  for (int k = row_offset_[i], end = row_offset_[i + 1]; k < end; ++k)
    if (row_d2_[k] < r2) out.push_back(row_index_[k]);
}

float RadiusSearch::nearestDistance(int i) const {
  if (table_radius_ > 0.f) {
    float best = std::numeric_limits<float>::infinity();
    for (int k = row_offset_[i], end = row_offset_[i + 1]; k < end; ++k)
      if (row_index_[k] != i) best = std::min(best, row_d2_[k]);
    if (std::isfinite(best)) return std::sqrt(best);
  }
  return impl_->nearest(i);
}

namespace {

// Neighbours within r of every point of an unorganized set: points bucketed into
// cubes of side r, each point's 27 surrounding cubes scanned.
void hashGridRows(const PointSet& set, float r, std::vector<int>& offset, std::vector<int>& index,
                  std::vector<float>& d2) {
  const int n = static_cast<int>(set.size());
  const double inv = 1.0 / r;
  auto cell = [&](const Eigen::Vector3f& p, int axis) { return detail::voxelCell(p[axis], inv); };
  const auto key = detail::voxelKey;
  std::vector<std::pair<std::uint64_t, int>> order(n);
  for (int i = 0; i < n; ++i) {
    const auto& p = set.points[i];
    order[i] = {key(cell(p, 0), cell(p, 1), cell(p, 2)), i};
  }
  std::sort(order.begin(), order.end());
  std::unordered_map<std::uint64_t, std::pair<int, int>> buckets;  // key -> [begin, end) in order
  buckets.reserve(order.size());
  for (int b = 0; b < n;) {
    int e = b;
    while (e < n && order[e].first == order[b].first) ++e;
    buckets.emplace(order[b].first, std::make_pair(b, e));
    b = e;
  }
  // Cell by cell: the points of one cell share their 27 cells' candidates, gathered and put in index
  // order once per cell, so each row comes out in ascending index without a sort of its own (on a
  // real crop's 1,368 points, 113 neighbours each: the rows' sorts were most of the table's time).
  // Rows are made in cell order and copied into index order at the end.
  const float r2 = r * r;
  std::vector<int> candidates;
  std::vector<int> made_index;
  std::vector<float> made_d2;
  std::vector<int> made_begin(n), made_count(n);
  made_index.reserve(static_cast<std::size_t>(n) * 64);
  made_d2.reserve(static_cast<std::size_t>(n) * 64);
  // The candidates of a cell (every point in its 27 cells), in index order without repeats: keys
  // alias only far beyond any view's range, where two of the 27 cells can share a bucket.
  auto gather = [&](std::int64_t cx, std::int64_t cy, std::int64_t cz, std::vector<int>& out) {
    out.clear();
    for (std::int64_t dx = -1; dx <= 1; ++dx)
      for (std::int64_t dy = -1; dy <= 1; ++dy)
        for (std::int64_t dz = -1; dz <= 1; ++dz) {
          const auto it = buckets.find(key(cx + dx, cy + dy, cz + dz));
          if (it == buckets.end()) continue;
          for (int k = it->second.first; k < it->second.second; ++k) out.push_back(order[k].second);
        }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
  };
  // Candidates' coordinates in rows, so that a point's distances to them are one loop the compiler
  // vectorises (the scalar loop over Vector3f was most of the table's time), summed as Eigen's
  // squaredNorm sums them (x + (y + z)): the rows hold the same floats.
  struct Rows {
    std::vector<float> x, y, z, d2;
    void fill(const PointSet& set, const std::vector<int>& points) {
      x.clear(), y.clear(), z.clear();
      for (int j : points) x.push_back(set.points[j].x()), y.push_back(set.points[j].y()), z.push_back(set.points[j].z());
      d2.resize(points.size());
    }
  };
  // Appends the candidates within r of p to the rows being made.
  auto appendWithin = [&](Rows& rows, const std::vector<int>& points, const Eigen::Vector3f& p) {
    const float px = p.x(), py = p.y(), pz = p.z();
    for (std::size_t c = 0; c < points.size(); ++c) {
      const float dx = rows.x[c] - px, dy = rows.y[c] - py, dz = rows.z[c] - pz;
      rows.d2[c] = dx * dx + (dy * dy + dz * dz);
    }
    for (std::size_t c = 0; c < points.size(); ++c)
      if (rows.d2[c] < r2) {
        made_index.push_back(points[c]);
        made_d2.push_back(rows.d2[c]);
      }
  };
  std::vector<int> own;  // a point whose bucket it shares with another cell's points (aliased keys)
  Rows cell_rows, own_rows;
  for (int b = 0; b < n;) {
    const int e = buckets.at(order[b].first).second;
    const auto& p0 = set.points[order[b].second];
    const std::int64_t cx = cell(p0, 0), cy = cell(p0, 1), cz = cell(p0, 2);
    gather(cx, cy, cz, candidates);
    cell_rows.fill(set, candidates);
    for (int k = b; k < e; ++k) {
      const int i = order[k].second;
      const auto& p = set.points[i];
      made_begin[i] = static_cast<int>(made_index.size());
      if (cell(p, 0) == cx && cell(p, 1) == cy && cell(p, 2) == cz) {
        appendWithin(cell_rows, candidates, p);
      } else {
        gather(cell(p, 0), cell(p, 1), cell(p, 2), own);
        own_rows.fill(set, own);
        appendWithin(own_rows, own, p);
      }
      made_count[i] = static_cast<int>(made_index.size()) - made_begin[i];
    }
    b = e;
  }
  offset.assign(n + 1, 0);
  for (int i = 0; i < n; ++i) offset[i + 1] = offset[i] + made_count[i];
  index.resize(offset[n]);
  d2.resize(offset[n]);
  for (int i = 0; i < n; ++i) {
    std::copy_n(made_index.begin() + made_begin[i], made_count[i], index.begin() + offset[i]);
    std::copy_n(made_d2.begin() + made_begin[i], made_count[i], d2.begin() + offset[i]);
  }
}

}  // namespace

void RadiusSearch::cacheNeighbourhoods(float radius) {
  row_offset_.clear();
  row_index_.clear();
  row_d2_.clear();
  table_radius_ = 0.f;
  if (!(radius > 0.f) || !set_) return;
  const int n = static_cast<int>(set_->size());
  if (impl_->grid()) {
    std::vector<int> nb;
    row_offset_.assign(n + 1, 0);
    for (int i = 0; i < n; ++i) {
      impl_->radius(i, radius, nb);
      for (int j : nb) {
        row_index_.push_back(j);
        row_d2_.push_back((set_->points[j] - set_->points[i]).squaredNorm());
      }
      row_offset_[i + 1] = static_cast<int>(row_index_.size());
    }
  } else {
    hashGridRows(*set_, radius, row_offset_, row_index_, row_d2_);
  }
  table_radius_ = radius;
}
bool RadiusSearch::usesGrid() const { return impl_->grid(); }

namespace {

// A float spacing worth naming when points coincide (1 mm: coordinates beyond ~8 km).
constexpr double kCoarseFloat = 1e-3;

std::string shortNumber(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.3g", v);
  return b;
}

// Points that coincide: how many distinct positions the set has.
std::size_t distinctPositions(const PointSet& set) {
  std::vector<std::array<float, 3>> p(set.size());
  for (std::size_t i = 0; i < set.size(); ++i) p[i] = {set.points[i].x(), set.points[i].y(), set.points[i].z()};
  std::sort(p.begin(), p.end());
  return static_cast<std::size_t>(std::unique(p.begin(), p.end()) - p.begin());
}

// The spacing of float coordinates where the set lies: the largest gap between adjacent floats
// over its largest |x|, |y|, |z|, and that coordinate.
std::pair<double, double> floatSpacing(const PointSet& set) {
  float far = 0.f;
  for (const auto& p : set.points) far = std::max(far, p.cwiseAbs().maxCoeff());
  return {static_cast<double>(std::nextafter(far, std::numeric_limits<float>::infinity()) - far),
          static_cast<double>(far)};
}

}  // namespace

double cloudResolution(const PointSet& set, const RadiusSearch& search) {
  if (set.size() < 2) throw Error("cloud resolution needs at least 2 valid points, got " +
                                  std::to_string(set.size()));
  // Squared distances are float: points farther apart than ~1.8e19 m overflow them.
  const auto [ulp, far] = floatSpacing(set);
  if (far > kMaxCoordinate)
    throw Error("degenerate cloud: coordinates up to " + shortNumber(far) + " m from the origin (beyond " +
                shortNumber(kMaxCoordinate) + " m, float distances overflow)");
  double sum = 0.0;
  std::size_t n = 0, apart = 0;
  for (std::size_t i = 0; i < set.size(); ++i) {
    const float d = search.nearestDistance(static_cast<int>(i));
    if (std::isfinite(d)) {
      sum += d;
      ++n;
      apart += d > 0.f ? 1 : 0;
    }
  }
  if (n == 0) throw Error("cloud resolution undefined: no point has a neighbour");
  const double resolution = sum / static_cast<double>(n);
  const double spacing = apart ? sum / static_cast<double>(apart) : 0.0;  // of the points with no twin
  // Far from the origin, float coordinates are coarser than the points' spacing: the view was
  // rounded onto a lattice when it was stored as float (too late to re-centre it here).
  const std::string where = " m from the origin, where float coordinates are " + shortNumber(ulp) + " m apart";
  const std::size_t distinct = resolution > 0 ? 0 : distinctPositions(set);
  if (!(resolution > 0))
    throw Error("degenerate cloud: its " + std::to_string(set.size()) + " points lie on only " +
                std::to_string(distinct) + (distinct == 1 ? " distinct position" : " distinct positions") +
                ", every one shared (nearest-neighbour distance 0, so no resolution)" +
                (ulp >= kCoarseFloat ? "; they lie up to " + shortNumber(far) + where : std::string()));
  if (ulp > spacing / 8)
    throw Error("degenerate cloud: " + std::to_string(set.size()) + " points up to " + shortNumber(far) + where +
                ", no finer than their spacing (" + shortNumber(spacing) + " m); store the view about its own origin");
  return resolution;
}

double cloudResolution(const PointSet& set) {
  RadiusSearch search(set);
  return cloudResolution(set, search);
}

}  // namespace keyturn
