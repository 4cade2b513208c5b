// The local complete graph (geodesic.h): every point joined to the points of its r-ball, the
// two-hop closure kept where no cheaper path exists, and the curvature-weighted twin.
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "graph_search.h"
#include "keyturn/core/error.h"

namespace keyturn {
namespace {

using detail::kInf;

Eigen::Vector3f pcaNormal(const PointSet& set, int i, const std::vector<int>& nb, int begin, int end) {
  if (end - begin < 2) return Eigen::Vector3f::Constant(std::nanf(""));
  Eigen::Vector3d mean = set.points[i].cast<double>();
  for (int k = begin; k < end; ++k) mean += set.points[nb[k]].cast<double>();
  mean /= static_cast<double>(end - begin + 1);
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  auto add = [&](const Eigen::Vector3f& p) {
    const Eigen::Vector3d d = p.cast<double>() - mean;
    cov.noalias() += d * d.transpose();
  };
  add(set.points[i]);
  for (int k = begin; k < end; ++k) add(set.points[nb[k]]);
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
  eig.computeDirect(cov);
  return eig.eigenvectors().col(0).cast<float>();  // smallest eigenvalue
}

// The curvature factor of an edge between vertices with normals a and b: max(sin θ, ε).
float curvatureFactor(const Eigen::Vector3f& a, const Eigen::Vector3f& b, float eps) {
  float c = 1.f;  // no normal: treat as maximally curved
  if (a.allFinite() && b.allFinite()) {
    const float d = std::min(1.f, std::abs(a.dot(b)));
    c = std::sqrt(1.f - d * d);  // sin(arccos(n_a·n_b))
  }
  return std::max(c, eps);
}

}  // namespace

LocalCompleteGraph buildLocalCompleteGraph(const PointSet& set, const RadiusSearch& search,
                                           double resolution, const GraphOptions& options) {
  const int n = static_cast<int>(set.size());
  const float r = static_cast<float>(options.radius * resolution);
  LocalCompleteGraph g;

  // r-ball neighbourhoods N(i), without i, in CSR form, with their lengths.
  std::vector<int> nb_off(n + 1, 0), nb;
  std::vector<float> nb_len;
  std::vector<int> tmp;
  for (int i = 0; i < n; ++i) {
    search.radius(i, r, tmp);
    for (int j : tmp)
      if (j != i) {
        nb.push_back(j);
        nb_len.push_back((set.points[j] - set.points[i]).norm());
      }
    nb_off[i + 1] = static_cast<int>(nb.size());
  }

  const bool weights = options.curvature_weights;
  const float eps = static_cast<float>(options.curvature_epsilon);
  if (weights) {
    g.normals.resize(n);
    for (int i = 0; i < n; ++i) g.normals[i] = pcaNormal(set, i, nb, nb_off[i], nb_off[i + 1]);
  }

  // adj(j) = N(j) ∪ ⋃_{i∈N(j)} N(i) \ {j}: the local complete graph. Each edge j–k comes with
  // its two-edge paths j–i–k through common neighbours i: the shortest such length is kept in
  // `via` (for the Euclidean graph's shortcut rule), the cheapest curved cost in `via_cost`.
  // Both rules are symmetric, so each edge is decided once, from its smaller end (k > j: the
  // rows N(i) are in ascending index order — search.radius's contract — and `after[i]` walks
  // past j as j grows), and written into both rows.
  std::vector<float> nb_cost;  // curved cost of each r-ball edge
  if (weights) {
    nb_cost.resize(nb.size());
    for (int i = 0; i < n; ++i)
      for (int a = nb_off[i]; a < nb_off[i + 1]; ++a)
        nb_cost[a] = curvatureFactor(g.normals[i], g.normals[nb[a]], eps) * nb_len[a];
  }
  struct Edge {  // j < k; every edge is in the Euclidean graph
    int j, k;
    float length, cost;
    bool curved;  // also in the curved one
  };
  std::vector<Edge> edges;
  edges.reserve(nb.size());
  std::vector<int> after(nb_off.begin(), nb_off.end() - 1);  // first entry of N(i) above j
  std::vector<int> mark(n, -1);
  std::vector<float> via(n, kInf), via_cost(weights ? n : 0, kInf);
  std::vector<int> seen;
  const float stretch = static_cast<float>(1.0 + std::max(0.0, options.shortcut_tolerance));
  const bool exact = !(options.shortcut_tolerance > 0.0);
  const bool prune_curved = options.curved_dominance_pruning;
  for (int j = 0; j < n; ++j) {
    const Eigen::Vector3f& pj = set.points[j];
    seen.clear();
    for (int a = nb_off[j]; a < nb_off[j + 1]; ++a) {  // N(j): direct edges, never left out of the Euclidean graph
      const int k = nb[a];
      mark[k] = j;
      via[k] = -1.f;
      if (weights) via_cost[k] = kInf;
      if (k > j) seen.push_back(k);
    }
    // The two-edge paths j–i–k, k > j, with or without their curved costs (one loop, compiled twice).
    auto paths = [&](auto with_cost) {
      constexpr bool kCost = decltype(with_cost)::value;
      for (int a = nb_off[j]; a < nb_off[j + 1]; ++a) {
        const int i = nb[a];
        const float ji = nb_len[a];
        const float cji = kCost ? nb_cost[a] : 0.f;
        int b = after[i];
        const int end = nb_off[i + 1];
        while (b < end && nb[b] <= j) ++b;
        after[i] = b;
        for (; b < end; ++b) {
          const int k = nb[b];
          if (mark[k] != j) {
            mark[k] = j;
            via[k] = kInf;
            if (kCost) via_cost[k] = kInf;
            seen.push_back(k);
          }
          via[k] = std::min(via[k], ji + nb_len[b]);  // a direct neighbour's −1 stays: every 2-path is > 0
          if (kCost) via_cost[k] = std::min(via_cost[k], cji + nb_cost[b]);
        }
      }
    };
    if (weights) paths(std::true_type());
    else paths(std::false_type());
    for (int k : seen) {
      const float len = (set.points[k] - pj).norm();
      if (!exact && via[k] >= 0.f && via[k] <= stretch * len) continue;  // a 2-path nearly as short
      Edge e{j, k, len, 0.f, false};
      if (weights) {
        e.cost = curvatureFactor(g.normals[j], g.normals[k], eps) * len;
        // Undercut by j–i–k, the edge is on no cheapest path: leaving it out changes no cost.
        e.curved = !(prune_curved && via_cost[k] < e.cost);
      }
      edges.push_back(e);
    }
  }

  // The CSR rows, each edge in both (rows in the order the edges were decided).
  auto rows = [&](std::vector<int>& offsets, auto keep) {
    offsets.assign(n + 1, 0);
    for (const Edge& e : edges)
      if (keep(e)) {
        ++offsets[e.j + 1];
        ++offsets[e.k + 1];
      }
    for (int v = 0; v < n; ++v) offsets[v + 1] += offsets[v];
    return std::vector<int>(offsets.begin(), offsets.end() - 1);  // the next free slot per row
  };
  {
    std::vector<int> slot = rows(g.offsets, [](const Edge&) { return true; });
    g.targets.resize(g.offsets[n]);
    g.length.resize(g.offsets[n]);
    for (const Edge& e : edges) {
      int s = slot[e.j]++;
      g.targets[s] = e.k, g.length[s] = e.length;
      s = slot[e.k]++;
      g.targets[s] = e.j, g.length[s] = e.length;
    }
  }
  if (weights) {
    std::vector<int> slot = rows(g.curved_offsets, [](const Edge& e) { return e.curved; });
    g.curved_targets.resize(g.curved_offsets[n]);
    g.curved_cost.resize(g.curved_offsets[n]);
    g.curved_length.resize(g.curved_offsets[n]);
    for (const Edge& e : edges) {
      if (!e.curved) continue;
      int s = slot[e.j]++;
      g.curved_targets[s] = e.k, g.curved_cost[s] = e.cost, g.curved_length[s] = e.length;
      s = slot[e.k]++;
      g.curved_targets[s] = e.j, g.curved_cost[s] = e.cost, g.curved_length[s] = e.length;
    }
  }
  return g;
}
}  // namespace keyturn
