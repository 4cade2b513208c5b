// Exact k nearest neighbours from a hash grid. The points of one cell share the candidates of the
// 27 cells around it (one set of hash lookups per cell, not per point); a point whose k-th
// neighbour could lie beyond them searches outward shell by shell, and one far from everything
// (an outlier) compares against every point once the shells would cost more than that.
#include "keyturn/core/nearest_neighbours.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>

#include "voxel_key.h"

namespace keyturn {

namespace {

// The k smallest values added so far, ascending (k is small: an insertion into a sorted run, by
// hand: most values are rejected by one compare, and a library insert was most of the time).
class SmallestK {
 public:
  explicit SmallestK(std::size_t k) : k_(k), v_(k) {}
  void clear() { size_ = 0; }
  bool full() const { return size_ == k_; }
  float worst() const { return v_[size_ - 1]; }
  void add(float d2) {
    std::size_t at = size_;
    if (full()) {
      if (!(d2 < v_[k_ - 1])) return;
      at = k_ - 1;
    } else {
      ++size_;
    }
    for (; at > 0 && d2 < v_[at - 1]; --at) v_[at] = v_[at - 1];
    v_[at] = d2;
  }
  const float* begin() const { return v_.data(); }
  const float* end() const { return v_.data() + size_; }

 private:
  std::size_t k_, size_ = 0;
  std::vector<float> v_;
};

// FLANN's L2_Simple: query minus point, summed x, y, z in that order.
inline float squaredDistance(const Eigen::Vector3f& q, const Eigen::Vector3f& p) {
  const float dx = q.x() - p.x(), dy = q.y() - p.y(), dz = q.z() - p.z();
  return dx * dx + dy * dy + dz * dz;
}

}  // namespace

std::vector<float> nearestSquaredDistances(const std::vector<Eigen::Vector3f>& pts, int k_in) {
  const std::size_t n = pts.size();
  const std::size_t k = std::min(static_cast<std::size_t>(std::max(k_in, 0)), n);
  if (k == 0) return {};
  Eigen::Vector3d lo = pts[0].cast<double>(), hi = lo;
  for (const auto& p : pts) {
    lo = lo.cwiseMin(p.cast<double>());
    hi = hi.cwiseMax(p.cast<double>());
  }
  Eigen::Vector3d extent = hi - lo;
  std::sort(extent.data(), extent.data() + 3, std::greater<double>());
  // A cell about 1.5 × the k-th neighbour's distance on a surface spanning the two largest extents,
  // counting at least 8 neighbours (the answer does not depend on it, the speed does: measured on
  // real crops, k = 13 and k = 2), and at most a million cells across, so cell indices counted from
  // the box's corner never alias in voxelKey.
  const double area = extent[1] > 0 ? extent[0] * extent[1] : extent[0] * extent[0];
  const double counted = static_cast<double>(std::max<std::size_t>(k, 8));
  double side = 1.5 * std::sqrt(area / static_cast<double>(n) * counted / M_PI);
  side = std::max(side, extent[0] * 1e-6);
  if (!(side > 0) || !std::isfinite(side)) side = 1.0;  // every point at one place
  const double inv = 1.0 / side;
  using Cell = Eigen::Matrix<std::int64_t, 3, 1>;
  auto cellOf = [&](const Eigen::Vector3f& p) {
    return Cell(detail::voxelCell(p.x() - lo.x(), inv), detail::voxelCell(p.y() - lo.y(), inv),
                detail::voxelCell(p.z() - lo.z(), inv));
  };
  auto keyOf = [](const Cell& c) { return detail::voxelKey(c.x(), c.y(), c.z()); };

  // Points in key order; a key orders cells by z, then y, then x, so the three cells x − 1 … x + 1
  // of one row are neighbours in it: a row of cells is one binary search in the occupied keys.
  std::vector<std::pair<std::uint64_t, int>> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = {keyOf(cellOf(pts[i])), static_cast<int>(i)};
  std::sort(order.begin(), order.end());
  std::vector<std::uint64_t> keys;  // each occupied cell's key, ascending
  std::vector<int> starts;          // its points' start in order (one past the last: starts.back())
  Cell top = Cell::Zero();          // the largest occupied cell index per axis (the smallest is 0)
  for (std::size_t m = 0; m < n; ++m)
    if (m == 0 || order[m].first != order[m - 1].first) {
      keys.push_back(order[m].first);
      starts.push_back(static_cast<int>(m));
      top = top.cwiseMax(cellOf(pts[order[m].second]));
    }
  starts.push_back(static_cast<int>(n));
  // Calls add(point) for every point in the cells (x0 … x1, y, z), x0 ≤ x1.
  auto addRow = [&](std::int64_t x0, std::int64_t x1, std::int64_t y, std::int64_t z, auto&& add) {
    if (x1 < 0 || y < 0 || z < 0 || x0 > top.x() || y > top.y() || z > top.z()) return;
    x0 = std::max<std::int64_t>(x0, 0), x1 = std::min<std::int64_t>(x1, top.x());
    const std::uint64_t last = detail::voxelKey(x1, y, z);
    for (auto it = std::lower_bound(keys.begin(), keys.end(), detail::voxelKey(x0, y, z)); it != keys.end() && *it <= last;
         ++it) {
      const auto cell = it - keys.begin();
      for (int m = starts[cell]; m < starts[cell + 1]; ++m) add(order[m].second);
    }
  };

  // The distance from q (in cell c) to the outside of the cube of cells c ± r.
  auto boundOutside = [&](const Eigen::Vector3f& q, const Cell& c, std::int64_t r) {
    double bound = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a) {
      const double x = static_cast<double>(q[a]) - lo[a];
      bound = std::min({bound, x - static_cast<double>(c[a] - r) * side, static_cast<double>(c[a] + r + 1) * side - x});
    }
    return bound;
  };

  std::vector<float> out(n * k);
  SmallestK best(k);
  std::vector<float> cx, cy, cz, d2, near;  // the candidates' coordinates and distances, in rows
  for (std::size_t cell = 0; cell < keys.size(); ++cell) {
    const Cell c = cellOf(pts[order[starts[cell]].second]);
    // The 27 cells' points, gathered once for all the points of this cell.
    cx.clear(), cy.clear(), cz.clear();
    for (std::int64_t dz = -1; dz <= 1; ++dz)
      for (std::int64_t dy = -1; dy <= 1; ++dy)
        addRow(c.x() - 1, c.x() + 1, c.y() + dy, c.z() + dz,
               [&](int j) { cx.push_back(pts[j].x()), cy.push_back(pts[j].y()), cz.push_back(pts[j].z()); });
    const std::size_t nc = cx.size();
    d2.resize(nc);
    near.resize(nc);
    const float *px = cx.data(), *py = cy.data(), *pz = cz.data();
    float* pd = d2.data();
    for (int m = starts[cell]; m < starts[cell + 1]; ++m) {
      const int i = order[m].second;
      const Eigen::Vector3f& q = pts[i];
      const float qx = q.x(), qy = q.y(), qz = q.z();
      for (std::size_t j = 0; j < nc; ++j) {  // as squaredDistance, in a loop the compiler vectorises
        const float dx = qx - px[j], dy = qy - py[j], dz = qz - pz[j];
        pd[j] = dx * dx + dy * dy + dz * dz;
      }
      // Only values below the 27 cells' bound can be among the k nearest once k of them are: they
      // are kept without a branch, and the selection sorts those few.
      const double safe27 = boundOutside(q, c, 1) * (1.0 - 1e-6);  // float distances' rounding, with room
      const float below = static_cast<float>(safe27 * safe27);
      std::size_t kept = 0;
      for (std::size_t j = 0; j < nc; ++j) {
        near[kept] = pd[j];
        kept += pd[j] < below ? 1 : 0;
      }
      best.clear();
      if (kept >= k) {
        for (std::size_t j = 0; j < kept; ++j) best.add(near[j]);
        std::copy(best.begin(), best.end(), out.begin() + static_cast<std::ptrdiff_t>(i * k));
        continue;
      }
      for (std::size_t j = 0; j < nc; ++j) best.add(pd[j]);
      for (std::int64_t r = 1;; ++r) {
        // Every point not yet seen lies outside the cube of cells c ± r: at least `bound` away.
        const double safe = boundOutside(q, c, r) * (1.0 - 1e-6);
        const bool everything = (c.array() - r <= 0).all() && (c.array() + r >= top.array()).all();
        if (everything || (best.full() && safe > 0 && static_cast<double>(best.worst()) <= safe * safe)) break;
        const std::int64_t s = r + 1;  // next: the cells at Chebyshev distance s from c
        const double rows_of_shell = (2.0 * static_cast<double>(s) + 1.0) * (2.0 * static_cast<double>(s) + 1.0);
        if (rows_of_shell > static_cast<double>(keys.size())) {
          best.clear();  // far from the rest (an outlier): every point, cheaper than the shells
          for (std::size_t j = 0; j < n; ++j) best.add(squaredDistance(q, pts[j]));
          break;
        }
        auto add = [&](int j) { best.add(squaredDistance(q, pts[j])); };
        for (std::int64_t dz = -s; dz <= s; ++dz)
          for (std::int64_t dy = -s; dy <= s; ++dy) {
            if (dz == -s || dz == s || dy == -s || dy == s) {
              addRow(c.x() - s, c.x() + s, c.y() + dy, c.z() + dz, add);  // a whole row on the shell
            } else {
              addRow(c.x() - s, c.x() - s, c.y() + dy, c.z() + dz, add);  // its two ends
              addRow(c.x() + s, c.x() + s, c.y() + dy, c.z() + dz, add);
            }
          }
      }
      std::copy(best.begin(), best.end(), out.begin() + static_cast<std::ptrdiff_t>(i * k));
    }
  }
  return out;
}

}  // namespace keyturn
