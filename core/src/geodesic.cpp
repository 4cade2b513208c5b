#include "keyturn/core/geodesic.h"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>
#include <algorithm>
#include <type_traits>

#include "keyturn/core/error.h"

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#include <immintrin.h>
#define KEYTURN_GEODESIC_AVX2 1
#endif

namespace keyturn {
namespace {
bool g_scalar_geodesics = false;  // detail::useScalarGeodesics

constexpr float kInf = std::numeric_limits<float>::infinity();

bool useAvx2() {
#ifdef KEYTURN_GEODESIC_AVX2
  static const bool has = __builtin_cpu_supports("avx2");
  return has && !g_scalar_geodesics;
#else
  return false;
#endif
}

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

// Indexed 4-ary min-heap of vertices keyed by cost: at most one entry per
// vertex (decrease-key instead of duplicates), so it never outgrows the graph.
class VertexHeap {
 public:
  explicit VertexHeap(std::size_t n) : pos_(n, -1) { heap_.reserve(n); }
  bool empty() const { return heap_.empty(); }
  void clear() {
    for (int v : heap_) pos_[v] = -1;
    heap_.clear();
  }
  void pushOrDecrease(int v, const float* key) {
    int i = pos_[v];
    if (i < 0) {
      i = static_cast<int>(heap_.size());
      heap_.push_back(v);
    }
    siftUp(i, v, key);
  }
  int pop(const float* key) {
    const int top = heap_[0];
    pos_[top] = -1;
    const int last = heap_.back();
    heap_.pop_back();
    if (!heap_.empty()) siftDown(last, key);
    return top;
  }

 private:
  void siftUp(int i, int v, const float* key) {
    const float k = key[v];
    while (i > 0) {
      const int parent = (i - 1) >> 2;
      const int pv = heap_[parent];
      if (key[pv] <= k) break;
      heap_[i] = pv;
      pos_[pv] = i;
      i = parent;
    }
    heap_[i] = v;
    pos_[v] = i;
  }
  void siftDown(int v, const float* key) {
    const int n = static_cast<int>(heap_.size());
    const float k = key[v];
    int i = 0;
    for (;;) {
      const int first = 4 * i + 1;
      if (first >= n) break;
      int best = first;
      float bk = key[heap_[first]];
      const int last = std::min(first + 4, n);
      for (int c = first + 1; c < last; ++c) {
        const float ck = key[heap_[c]];
        if (ck < bk) {
          bk = ck;
          best = c;
        }
      }
      if (bk >= k) break;
      heap_[i] = heap_[best];
      pos_[heap_[i]] = i;
      i = best;
    }
    heap_[i] = v;
    pos_[v] = i;
  }
  std::vector<int> heap_;
  std::vector<int> pos_;
};

// Dijkstra over the CSR graph. Cost is the Euclidean length or the curvature-
// weighted cost; for the latter `euclid` carries the Euclidean length of the
// path that minimises the cost. Stops once `remaining` targets have settled.
class Dijkstra {
 public:
  explicit Dijkstra(const LocalCompleteGraph& g)
      : g_(g), cost_(g.vertexCount(), kInf), euclid_(g.vertexCount(), kInf),
        settled_(g.vertexCount(), 0), heap_(g.vertexCount()) {}

  template <typename OnSettle>
  void run(int source, bool curved, int remaining, OnSettle&& on_settle) {
    if (curved) runImpl<true>(source, remaining, on_settle);
    else runImpl<false>(source, remaining, on_settle);
  }

 private:
  template <bool Curved, typename OnSettle>
  void runImpl(int source, int remaining, OnSettle& on_settle) {
    for (int v : touched_) {
      cost_[v] = kInf;
      if (Curved) euclid_[v] = kInf;
      settled_[v] = 0;
    }
    touched_.clear();
    heap_.clear();
    const int* off = Curved ? g_.curved_offsets.data() : g_.offsets.data();
    float* cost = cost_.data();
    const bool avx2 = useAvx2();
    cost[source] = 0.f;
    if (Curved) euclid_[source] = 0.f;
    touched_.push_back(source);
    heap_.pushOrDecrease(source, cost);
    while (!heap_.empty()) {
      const int v = heap_.pop(cost);
      settled_[v] = 1;
      if (on_settle(v, Curved ? euclid_[v] : cost[v]) && --remaining <= 0) return;
#ifdef KEYTURN_GEODESIC_AVX2
      if (avx2) {
        relaxAvx2<Curved>(v, off[v], off[v + 1]);
        continue;
      }
#endif
      for (int e = off[v], end = off[v + 1]; e < end; ++e) relax<Curved>(v, e);
    }
  }

  // Relaxes edge e of the settled vertex v.
  template <bool Curved>
  void relax(int v, int e) {
    const float* w = Curved ? g_.curved_cost.data() : g_.length.data();
    const int t = (Curved ? g_.curved_targets : g_.targets)[e];
    const float nc = cost_[v] + w[e];
    if (nc < cost_[t]) {
      if (settled_[t]) return;  // rounding only: settled costs are final
      if (cost_[t] == kInf) touched_.push_back(t);
      cost_[t] = nc;
      if (Curved) euclid_[t] = euclid_[v] + g_.curved_length[e];
      heap_.pushOrDecrease(t, cost_.data());
    }
  }

#ifdef KEYTURN_GEODESIC_AVX2
  // Most relaxations improve nothing (about 95 % for plain lengths, 80 % for curved costs), so eight
  // edges are compared at once — one gather of their targets' costs — and only the lanes that improve
  // go, in edge order, through the same relax(): the same float operations in the same order as the
  // scalar loop, so both give bit-identical results (tested). relax() compares again with the current
  // cost, and costs only fall, so a lane the block's compare passes over the scalar loop would too.
  template <bool Curved>
  __attribute__((target("avx2"))) void relaxAvx2(int v, int begin, int end) {
    const float* w = Curved ? g_.curved_cost.data() : g_.length.data();
    const int* tgt = Curved ? g_.curved_targets.data() : g_.targets.data();
    const float* cost = cost_.data();
    const __m256 c = _mm256_set1_ps(cost_[v]);
    int e = begin;
    for (; e + 8 <= end; e += 8) {
      const __m256i t = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(tgt + e));
      const __m256 nc = _mm256_add_ps(c, _mm256_loadu_ps(w + e));
      const __m256 old = _mm256_i32gather_ps(cost, t, 4);
      unsigned lanes = static_cast<unsigned>(_mm256_movemask_ps(_mm256_cmp_ps(nc, old, _CMP_LT_OQ)));
      while (lanes) {
        relax<Curved>(v, e + __builtin_ctz(lanes));
        lanes &= lanes - 1;
      }
    }
    for (; e < end; ++e) relax<Curved>(v, e);
  }
#endif

  const LocalCompleteGraph& g_;
  std::vector<float> cost_, euclid_;
  std::vector<char> settled_;
  VertexHeap heap_;
  std::vector<int> touched_;
};

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

void detail::useScalarGeodesics(bool scalar) { g_scalar_geodesics = scalar; }
bool detail::geodesicsUseAvx2() { return useAvx2(); }

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
