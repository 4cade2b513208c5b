#include "keyturn/core/geodesic.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>

#include "graph_search.h"
#include "keyturn/core/error.h"

namespace keyturn {

using detail::Dijkstra;
using detail::kInf;

std::vector<float> shortestPathLengths(const LocalCompleteGraph& graph, int source, bool curvature) {
  if (curvature && !graph.hasCurvedGraph()) throw Error("curvature-weighted paths need a graph built with curvature weights");
  std::vector<float> out(graph.vertexCount(), kInf);
  Dijkstra dj(graph);
  dj.run(source, curvature, std::numeric_limits<int>::max(), [&](int v, float e) {
    out[v] = e;
    return false;
  });
  return out;
}

std::vector<std::vector<int>> shortestPaths(const LocalCompleteGraph& graph, int source,
                                            const std::vector<int>& targets) {
  const std::vector<float> cost = shortestPathLengths(graph, source, false);
  // Walk back from each target: the predecessor is the neighbour whose cost plus
  // the edge gives this vertex's cost (the smallest such sum, so float rounding
  // cannot leave the walk without a step). Costs strictly fall, so it ends at source.
  std::vector<std::vector<int>> paths;
  for (int t : targets) {
    std::vector<int> path;
    if (t >= 0 && static_cast<std::size_t>(t) < cost.size() && cost[t] < kInf) {
      int v = t;
      path.push_back(v);
      while (v != source) {
        int best = -1;
        float best_cost = kInf;
        for (int e = graph.offsets[v]; e < graph.offsets[v + 1]; ++e) {
          const int u = graph.targets[e];
          if (cost[u] < cost[v] && cost[u] + graph.length[e] < best_cost) {
            best_cost = cost[u] + graph.length[e];
            best = u;
          }
        }
        if (best < 0) break;  // cannot happen on a consistent graph; never loop
        v = best;
        path.push_back(v);
      }
      std::reverse(path.begin(), path.end());
    }
    paths.push_back(std::move(path));
  }
  return paths;
}

GeodesicResult geodesicKeypointDistances(const LocalCompleteGraph& graph, const PointSet& set,
                                         const std::vector<int>& keypoints, int which,
                                         const std::vector<double>* weights, int centroid_sources) {
  GeodesicResult res;
  const int n = static_cast<int>(graph.vertexCount());
  const int k = static_cast<int>(keypoints.size());
  if (n == 0 || k == 0) return res;
  Dijkstra dj(graph);
  // Pairs are symmetric, so source a only needs keypoints after it. Taking each next
  // source from the outside in — the one farthest from the centroid of the keypoints still
  // left — leaves a shrinking, compact set of targets, so later searches stop sooner
  // (9 % fewer vertices settled than with one centroid of all keypoints, on the benchmark view).
  std::vector<int> order;
  order.reserve(k);
  {
    std::vector<int> left(keypoints);
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (int v : left) sum += set.points[v].cast<double>();
    while (!left.empty()) {
      const Eigen::Vector3f c = (sum / static_cast<double>(left.size())).cast<float>();
      std::size_t far = 0;
      float far_d = -1.f;
      for (std::size_t q = 0; q < left.size(); ++q) {
        const float d = (set.points[left[q]] - c).squaredNorm();
        if (d > far_d) far_d = d, far = q;
      }
      order.push_back(left[far]);
      sum -= set.points[left[far]].cast<double>();
      left.erase(left.begin() + static_cast<std::ptrdiff_t>(far));
    }
  }
  std::vector<int> slot(n, -1);
  for (int a = 0; a < k; ++a) slot[order[a]] = a;
  std::vector<double> weight_of;  // per vertex, only with weights
  if (weights) {
    weight_of.assign(n, 0.0);
    for (int a = 0; a < k; ++a) weight_of[keypoints[a]] = (*weights)[a];
  }

  if (which & kGkpd1) {
    // GKPD1: from the centroid, through the vertices nearest it (GraphOptions::centroid_sources).
    const CentroidSources sources = centroidSources(set, centroid_sources);
    res.centroid_vertex = sources.vertex.empty() ? -1 : sources.vertex.front();
    if (sources.vertex.size() == 1) {
      dj.run(res.centroid_vertex, false, k, [&](int v, float e) {
        if (slot[v] < 0) return false;
        res.gkpd1.push_back(e);
        if (weights) res.gkpd1_weight.push_back(static_cast<float>(weight_of[v]));
        return true;
      });
    } else {
      // Per keypoint (by slot): the weighted sum of its distances and of the weights that reached it.
      std::vector<double> sum(k, 0.0), reached(k, 0.0);
      for (std::size_t s = 0; s < sources.vertex.size(); ++s)
        dj.run(sources.vertex[s], false, k, [&](int v, float e) {
          if (slot[v] < 0) return false;
          sum[slot[v]] += sources.weight[s] * e;
          reached[slot[v]] += sources.weight[s];
          return true;
        });
      for (int a = 0; a < k; ++a) {
        if (!(reached[a] > 0)) continue;
        res.gkpd1.push_back(static_cast<float>(sum[a] / reached[a]));
        if (weights) res.gkpd1_weight.push_back(static_cast<float>(weight_of[order[a]]));
      }
    }
    res.unreachable_from_centroid = k - static_cast<int>(res.gkpd1.size());
  }

  // GKPD2 / GKPCD2 over unordered pairs: the graph is undirected with symmetric
  // costs, so the path a→b is b→a reversed; each source only needs later keypoints.
  for (int pass = 0; pass < 2; ++pass) {
    const bool curved = pass == 1;
    if (!(which & (curved ? kGkpcd2 : kGkpd2))) continue;
    if (curved && !graph.hasCurvedGraph())
      throw Error("GKPCD2 needs a graph built with curvature weights");
    std::vector<float>& out = curved ? res.gkpcd2 : res.gkpd2;
    std::vector<float>& out_weight = curved ? res.gkpcd2_weight : res.gkpd2_weight;
    int unreachable = 0;
    for (int a = 0; a + 1 < k; ++a) {
      int found = 0;
      dj.run(order[a], curved, k - 1 - a, [&](int v, float e) {
        if (slot[v] <= a) return false;
        out.push_back(e);
        if (weights) out_weight.push_back(static_cast<float>(weight_of[order[a]] * weight_of[v]));
        ++found;
        return true;
      });
      unreachable += k - 1 - a - found;
    }
    res.unreachable_pairs = unreachable;
  }
  return res;
}

int centroidVertex(const PointSet& set) {
  const Eigen::Vector3f c = set.centroid();
  int vertex = -1;
  float best = kInf;
  for (std::size_t v = 0; v < set.points.size(); ++v) {
    const float d = (set.points[v] - c).squaredNorm();
    if (d < best) {
      best = d;
      vertex = static_cast<int>(v);
    }
  }
  return vertex;
}

CentroidSources centroidSources(const PointSet& set, int m) {
  CentroidSources out;
  const std::size_t n = set.points.size();
  if (n == 0) return out;
  m = std::max(1, m);
  if (m == 1) {
    out.vertex = {centroidVertex(set)};
    out.weight = {1.0};
    return out;
  }
  const Eigen::Vector3f c = set.centroid();
  // The m + 1 nearest, by (distance, index) so ties are decided the same way every time.
  std::vector<std::pair<float, int>> d(n);
  for (std::size_t v = 0; v < n; ++v) d[v] = {(set.points[v] - c).norm(), static_cast<int>(v)};
  const std::size_t take = std::min<std::size_t>(static_cast<std::size_t>(m) + 1, n);
  std::partial_sort(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(take), d.end());
  const std::size_t used = std::min<std::size_t>(static_cast<std::size_t>(m), n);
  // With fewer than m + 1 vertices there is no (m+1)-th to fade against: equal weights.
  const double fade_to = take > used ? d[used].first : 0.0;
  double total = 0.0;
  for (std::size_t i = 0; i < used; ++i) {
    out.vertex.push_back(d[i].second);
    out.weight.push_back(take > used ? fade_to - d[i].first : 1.0);
    total += out.weight.back();
  }
  if (!(total > 0)) {  // the m + 1 nearest all equally far: no vertex is nearer than another
    out.weight.assign(used, 1.0);
    total = static_cast<double>(used);
  }
  for (double& w : out.weight) w /= total;
  return out;
}

std::vector<std::vector<Eigen::Vector3f>> centroidGeodesicPolylines(const LocalCompleteGraph& graph, const PointSet& set,
                                                                    const std::vector<int>& keypoints) {
  std::vector<std::vector<Eigen::Vector3f>> out;
  if (set.points.empty() || keypoints.empty() || graph.vertexCount() != set.points.size()) return out;
  for (const auto& path : shortestPaths(graph, centroidVertex(set), keypoints)) {
    if (path.empty()) continue;
    std::vector<Eigen::Vector3f> line;
    for (int v : path) line.push_back(set.points[static_cast<std::size_t>(v)]);
    out.push_back(std::move(line));
  }
  return out;
}

}  // namespace keyturn

