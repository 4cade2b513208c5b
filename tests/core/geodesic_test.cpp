#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>

#include "keyturn/core/error.h"
#include "keyturn/core/filter.h"
#include "keyturn/core/geodesic.h"
#include "keyturn/sim/tof_view.h"
#include "support/synthetic_clouds.h"

using namespace keyturn;

namespace {
constexpr float kR = 0.05f, kH = 0.1f;
constexpr int kAround = 126, kRings = 41;  // ≈ 2.5 mm spacing both ways

int cylinderVertex(int around_index, int ring) { return ring * kAround + around_index; }

struct CylinderGraph {
  PointSet set;
  std::unique_ptr<RadiusSearch> search;
  double res = 0;
  LocalCompleteGraph graph;
  CylinderGraph() {
    set = PointSet::fromCloud(test::unorganized(test::cylinderSurface(kR, kH, kAround, kRings)));
    search = std::make_unique<RadiusSearch>(set);
    res = cloudResolution(set, *search);
    graph = buildLocalCompleteGraph(set, *search, res, GraphOptions());
  }
};
// The surfaces the graph tests compare two graphs on: a cylinder and the benchmark mug as filtered.
struct GraphInput {
  PointSet set;
  std::unique_ptr<RadiusSearch> search;
  double res = 0;
  explicit GraphInput(PointSet s) : set(std::move(s)) {
    search = std::make_unique<RadiusSearch>(set);
    res = cloudResolution(set, *search);
  }
  LocalCompleteGraph graph(const GraphOptions& o) const { return buildLocalCompleteGraph(set, *search, res, o); }
};
std::vector<std::unique_ptr<GraphInput>> cylinderAndMug() {
  std::vector<std::unique_ptr<GraphInput>> out;
  out.push_back(std::make_unique<GraphInput>(
      PointSet::fromCloud(test::unorganized(test::cylinderSurface(kR, kH, kAround, kRings)))));
  out.push_back(std::make_unique<GraphInput>(PointSet::fromCloud(filterCloud(sim::builtinBenchmarkView(), FilterOptions()))));
  return out;
}

// Path lengths from 8 spread sources on `other` against `reference`: the least and largest relative
// excess, the largest difference, and how many vertices were compared (reachability must agree).
struct PathComparison {
  double least_excess = 1.0, worst_excess = -1.0, worst_difference = 0.0;
  int compared = 0;
};
PathComparison comparePaths(const LocalCompleteGraph& reference, const LocalCompleteGraph& other, bool curved) {
  PathComparison c;
  const int n = static_cast<int>(reference.vertexCount());
  for (int source = 0; source < n; source += n / 7) {
    const auto d0 = shortestPathLengths(reference, source, curved);
    const auto d1 = shortestPathLengths(other, source, curved);
    for (int v = 0; v < n; ++v) {
      EXPECT_EQ(std::isfinite(d0[v]), std::isfinite(d1[v])) << "vertex " << v << " from " << source;
      if (!std::isfinite(d0[v]) || !std::isfinite(d1[v]) || d0[v] <= 0.f) continue;
      const double excess = static_cast<double>(d1[v] / d0[v]) - 1.0;
      c.least_excess = std::min(c.least_excess, excess);
      c.worst_excess = std::max(c.worst_excess, excess);
      c.worst_difference = std::max(c.worst_difference, std::abs(excess));
      ++c.compared;
    }
  }
  return c;
}
}  // namespace

TEST(LocalCompleteGraph, EdgesAreExactlyTheTwoHopClosure) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.f, 0.1f);
  std::vector<Eigen::Vector3f> pts;
  for (int i = 0; i < 150; ++i) pts.emplace_back(u(rng), u(rng), 1.f + 0.2f * u(rng));
  const PointSet set = PointSet::fromCloud(test::unorganized(pts));
  const RadiusSearch search(set);
  const double res = cloudResolution(set, search);
  GraphOptions exact;
  exact.shortcut_tolerance = 0.0;
  const auto g = buildLocalCompleteGraph(set, search, res, exact);
  const float r = static_cast<float>(3.5 * res);
  std::set<std::pair<int, int>> expect;
  const int n = static_cast<int>(pts.size());
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      if (j == i || (pts[i] - pts[j]).norm() >= r) continue;
      expect.insert({i, j});  // centre joined to its neighbour
      for (int k = 0; k < n; ++k)
        if (k != j && (pts[i] - pts[k]).norm() < r) expect.insert({j, k});  // neighbours joined
    }
  std::set<std::pair<int, int>> got;
  for (int v = 0; v < n; ++v)
    for (int e = g.offsets[v]; e < g.offsets[v + 1]; ++e) got.insert({v, g.targets[e]});
  EXPECT_EQ(got, expect);
  EXPECT_GT(got.size(), 300u);
}

TEST(Geodesic, AroundACylinderMatchesTheArc) {
  CylinderGraph c;
  const int a = cylinderVertex(0, 20), b = cylinderVertex(kAround / 4, 20);
  const auto d = shortestPathLengths(c.graph, a, false);
  const double arc = kR * M_PI / 2;
  EXPECT_NEAR(d[b], arc, 0.02 * arc);
  // Far longer than the straight chord through the cylinder.
  EXPECT_GT(d[b], 1.08 * (c.set.points[a] - c.set.points[b]).norm());
}

TEST(Geodesic, HelixOnACylinderMatchesTheUnrolledLength) {
  CylinderGraph c;
  const int a = cylinderVertex(0, 8), b = cylinderVertex(kAround / 4, 32);
  const double rise = kH * (32 - 8) / (kRings - 1), arc = kR * M_PI / 2;
  const double analytic = std::hypot(arc, rise);
  const auto d = shortestPathLengths(c.graph, a, false);
  EXPECT_NEAR(d[b], analytic, 0.03 * analytic);
}

TEST(Geodesic, CurvatureWeightedPathIsLongerOnACurvedSurface) {
  CylinderGraph c;
  const int a = cylinderVertex(0, 8), b = cylinderVertex(kAround / 4, 32);
  const GeodesicResult r = geodesicKeypointDistances(c.graph, c.set, {a, b}, kGkpd2 | kGkpcd2);
  ASSERT_EQ(r.gkpd2.size(), 1u);
  ASSERT_EQ(r.gkpcd2.size(), 1u);
  // Along the axis the normals agree (C ≈ ε): the weighted path climbs first,
  // then goes around — an L, longer than the helix.
  const double rise = kH * 24 / (kRings - 1), arc = kR * M_PI / 2;
  EXPECT_GT(r.gkpcd2[0], 1.2 * r.gkpd2[0]);
  EXPECT_NEAR(r.gkpcd2[0], rise + arc, 0.06 * (rise + arc));
}

TEST(Geodesic, KeypointsInAnotherComponentAreCountedNotHistogrammed) {
  auto pts = test::cylinderSurface(kR, kH, 60, 20);
  const std::size_t first = pts.size();
  for (const auto& p : test::cylinderSurface(kR, kH, 60, 20)) pts.push_back(p + Eigen::Vector3f(0.5f, 0, 0));
  const PointSet set = PointSet::fromCloud(test::unorganized(pts));
  const RadiusSearch search(set);
  const double res = cloudResolution(set, search);
  const auto g = buildLocalCompleteGraph(set, search, res, GraphOptions());
  const std::vector<int> kp = {0, 30, static_cast<int>(first), static_cast<int>(first) + 30};
  const GeodesicResult r = geodesicKeypointDistances(g, set, kp, kAllGeodesics);
  EXPECT_EQ(r.unreachable_pairs, 4);  // 2 × 2 pairs across the gap
  EXPECT_EQ(r.gkpd2.size(), 2u);
  EXPECT_EQ(r.gkpcd2.size(), 2u);
  EXPECT_EQ(r.unreachable_from_centroid + static_cast<int>(r.gkpd1.size()), 4);
  EXPECT_EQ(r.unreachable_from_centroid, 2);
  for (float v : r.gkpd2) EXPECT_TRUE(std::isfinite(v));
}

TEST(Geodesic, PairsAreSymmetric) {
  CylinderGraph c;
  const int a = cylinderVertex(3, 5), b = cylinderVertex(70, 30);
  EXPECT_FLOAT_EQ(shortestPathLengths(c.graph, a, false)[b], shortestPathLengths(c.graph, b, false)[a]);
}

TEST(Geodesic, PathsFollowTheSurfaceAndSumToTheDistance) {
  const CylinderGraph c;
  const int source = cylinderVertex(0, 20), half = cylinderVertex(kAround / 2, 20), up = cylinderVertex(0, 40);
  const auto len = shortestPathLengths(c.graph, source, false);
  const auto paths = shortestPaths(c.graph, source, {half, up, -1});
  ASSERT_EQ(paths.size(), 3u);
  EXPECT_TRUE(paths[2].empty());  // not a vertex
  for (int p = 0; p < 2; ++p) {
    const auto& path = paths[p];
    ASSERT_GE(path.size(), 3u);
    EXPECT_EQ(path.front(), source);
    EXPECT_EQ(path.back(), p == 0 ? half : up);
    float sum = 0;
    for (std::size_t i = 1; i < path.size(); ++i) {
      const float step = (c.set.points[path[i]] - c.set.points[path[i - 1]]).norm();
      EXPECT_LE(step, 2 * 3.5 * c.res + 1e-6);  // consecutive vertices are graph neighbours
      sum += step;
    }
    EXPECT_NEAR(sum, len[path.back()], 1e-4);
  }
  // half way round: close to the arc π r, far longer than the chord 2 r
  const auto& hp = paths[0];
  float arc = 0;
  for (std::size_t i = 1; i < hp.size(); ++i) arc += (c.set.points[hp[i]] - c.set.points[hp[i - 1]]).norm();
  EXPECT_NEAR(arc, M_PI * kR, 0.03 * M_PI * kR);
}

TEST(Geodesic, CentroidPolylinesEndAtEachReachableKeypoint) {
  const CylinderGraph c;
  const std::vector<int> kp = {cylinderVertex(0, 0), cylinderVertex(kAround / 2, 40), cylinderVertex(10, 20)};
  const auto lines = centroidGeodesicPolylines(c.graph, c.set, kp);
  ASSERT_EQ(lines.size(), 3u);
  for (std::size_t i = 0; i < kp.size(); ++i) {
    ASSERT_GE(lines[i].size(), 2u);
    EXPECT_TRUE(lines[i].back().isApprox(c.set.points[kp[i]]));
    // All start at the same vertex: the one nearest the centroid (on the axis, so r away).
    EXPECT_TRUE(lines[i].front().isApprox(lines[0].front()));
    EXPECT_NEAR(std::hypot(lines[i].front().x(), lines[i].front().y()), kR, 1e-4);
    EXPECT_NEAR(lines[i].front().z(), kH / 2, 0.01);
    EXPECT_TRUE(lines[i].front().isApprox(c.set.points[static_cast<std::size_t>(centroidVertex(c.set))]));
  }
  // A graph of other points is not this view's: no paths rather than paths through the wrong vertices.
  EXPECT_TRUE(centroidGeodesicPolylines(LocalCompleteGraph(), c.set, kp).empty());
}

TEST(Geodesic, WithoutCurvatureWeightsTheLengthsAreTheSame) {
  const CylinderGraph c;
  GraphOptions o;
  o.curvature_weights = false;
  const auto lean = buildLocalCompleteGraph(c.set, *c.search, c.res, o);
  EXPECT_TRUE(lean.normals.empty());
  EXPECT_TRUE(lean.curved_targets.empty());
  EXPECT_FALSE(lean.hasCurvedGraph());
  EXPECT_EQ(lean.targets, c.graph.targets);
  EXPECT_EQ(lean.length, c.graph.length);
  const std::vector<int> kp = {cylinderVertex(0, 0), cylinderVertex(30, 20), cylinderVertex(70, 40)};
  const auto full = geodesicKeypointDistances(c.graph, c.set, kp, kGkpd1 | kGkpd2);
  const auto part = geodesicKeypointDistances(lean, c.set, kp, kGkpd1 | kGkpd2);
  EXPECT_EQ(full.gkpd1, part.gkpd1);
  EXPECT_EQ(full.gkpd2, part.gkpd2);
  EXPECT_THROW(geodesicKeypointDistances(lean, c.set, kp, kGkpcd2), Error);
}

// The default graph leaves out the 2-hop edges that a path through a common neighbour
// nearly matches: it keeps every r-ball edge, over a quarter fewer edges in all, and every
// distance within 1 % of the exact local complete graph's (never shorter).
TEST(LocalCompleteGraph, ShortcutFreeGraphKeepsDistancesWithinOnePercent) {
  for (const auto& in : cylinderAndMug()) {
    GraphOptions exact_options;
    exact_options.shortcut_tolerance = 0.0;
    const auto exact = in->graph(exact_options);
    const auto sparse = in->graph(GraphOptions());
    EXPECT_LT(sparse.edgeCount() * 4, exact.edgeCount() * 3);  // measured: 38 % fewer on the mug
    const PathComparison c = comparePaths(exact, sparse, false);
    EXPECT_GT(c.compared, 1000);
    EXPECT_GE(c.least_excess, -1e-5) << "a sparse-graph distance shorter than the exact graph's";
    EXPECT_LE(c.worst_excess, 0.01) << "worst relative excess over the exact graph";
  }
}

// The AVX2 relaxation compares eight edges at once and hands the improving ones, in edge order,
// to the scalar update: on the benchmark view (every pair of its ISS keypoints, both costs) and on
// the cylinder every distance is the scalar loop's to the bit.
TEST(Geodesic, VectorisedSearchesAreBitIdenticalToTheScalarLoop) {
  // A plain skip, also on CI: the machine's CPU is not CI's to choose.
  if (!detail::geodesicsUseAvx2()) GTEST_SKIP() << "this CPU has no AVX2: only the scalar loop runs";
  const Cloud view = filterCloud(sim::builtinBenchmarkView(), FilterOptions());
  const PointSet mug = PointSet::fromCloud(view);
  const RadiusSearch search(mug);
  const double res = cloudResolution(mug, search);
  const LocalCompleteGraph graph = buildLocalCompleteGraph(mug, search, res, GraphOptions());
  std::vector<int> kp;
  for (int v = 0; v < static_cast<int>(mug.size()); v += 37) kp.push_back(v);  // 56 spread vertices
  const GeodesicResult fast = geodesicKeypointDistances(graph, mug, kp);
  const std::vector<float> fast_curved = shortestPathLengths(graph, kp[3], true);
  const CylinderGraph c;
  const std::vector<float> fast_cyl = shortestPathLengths(c.graph, 0, false);
  detail::useScalarGeodesics(true);
  EXPECT_FALSE(detail::geodesicsUseAvx2());
  const GeodesicResult slow = geodesicKeypointDistances(graph, mug, kp);
  const std::vector<float> slow_curved = shortestPathLengths(graph, kp[3], true);
  const std::vector<float> slow_cyl = shortestPathLengths(c.graph, 0, false);
  detail::useScalarGeodesics(false);
  ASSERT_EQ(fast.gkpd2.size(), kp.size() * (kp.size() - 1) / 2 - static_cast<std::size_t>(fast.unreachable_pairs));
  EXPECT_EQ(fast.gkpd1, slow.gkpd1);
  EXPECT_EQ(fast.gkpd2, slow.gkpd2);
  EXPECT_EQ(fast.gkpcd2, slow.gkpcd2);
  EXPECT_EQ(fast_curved, slow_curved);
  EXPECT_EQ(fast_cyl, slow_cyl);
}

// GKPCD2's graph leaves out the edges a two-edge path through a common neighbour undercuts in
// curved cost. Such an edge lies on no cheapest path, so every cheapest path, and with it the
// Euclidean length GKPCD2 reports, is the one the whole edge set gives (to float rounding: the
// relaxations come in another order). The Euclidean graph is untouched and the curved one stays
// undirected.
TEST(LocalCompleteGraph, CurvedGraphLeavesOutOnlyEdgesNoCheapestPathTakes) {
  for (const auto& in : cylinderAndMug()) {
    GraphOptions whole_options;
    whole_options.curved_dominance_pruning = false;
    const auto whole = in->graph(whole_options);
    const auto pruned = in->graph(GraphOptions());
    EXPECT_EQ(pruned.targets, whole.targets);
    EXPECT_EQ(pruned.length, whole.length);
    EXPECT_EQ(whole.curved_targets, whole.targets);
    EXPECT_LT(pruned.curvedEdgeCount() * 5, whole.curvedEdgeCount());  // measured: 10 % kept on the mug, 9 % on the cylinder
    std::set<std::pair<int, int>> edges;
    for (int v = 0; v < static_cast<int>(pruned.vertexCount()); ++v)
      for (int e = pruned.curved_offsets[v]; e < pruned.curved_offsets[v + 1]; ++e)
        edges.insert({v, pruned.curved_targets[e]});
    for (const auto& [a, b] : edges) ASSERT_TRUE(edges.count({b, a})) << a << "–" << b << " one way only";
    const PathComparison c = comparePaths(whole, pruned, true);
    EXPECT_GT(c.compared, 1000);
    EXPECT_LE(c.worst_difference, 1e-5) << "worst relative difference from the whole edge set's paths";
  }
}

// GKPD1's source (GraphOptions::centroid_sources). On a 20 × 20 grid the centroid is the centre of a
// cell, as near to its four corners as can be; moving a far corner of the grid by ±1 mm moves the
// centroid by micrometres and decides which corner is "nearest". With one source every GKPD1 value
// jumps by about a grid step; blending the four corners by how much nearer each is than the fifth
// vertex, the values move by what the centroid moved.
TEST(Geodesic, BlendedCentroidSourcesMoveGkpd1ContinuouslyWithTheView) {
  constexpr int kSide = 20;
  constexpr float kStep = 0.005f;
  const auto gkpd1 = [&](float corner_shift, int sources) {
    std::vector<Eigen::Vector3f> pts;
    for (int i = 0; i < kSide; ++i)
      for (int j = 0; j < kSide; ++j) pts.emplace_back(kStep * static_cast<float>(i), kStep * static_cast<float>(j), 0.f);
    pts[0].x() += corner_shift;
    const PointSet set = PointSet::fromCloud(test::unorganized(pts));
    const RadiusSearch search(set);
    const double res = cloudResolution(set, search);
    const auto g = buildLocalCompleteGraph(set, search, res, GraphOptions());
    std::vector<int> kp;  // the far column (x = 95 mm)
    for (int j = 0; j < kSide; j += 3) kp.push_back((kSide - 1) * kSide + j);
    const CentroidSources s = centroidSources(set, sources);
    EXPECT_EQ(static_cast<int>(s.vertex.size()), sources);
    double total = 0;
    for (double w : s.weight) total += w;
    EXPECT_NEAR(total, 1.0, 1e-12);
    auto v = geodesicKeypointDistances(g, set, kp, kGkpd1, nullptr, sources).gkpd1;
    EXPECT_EQ(v.size(), kp.size());
    std::sort(v.begin(), v.end());
    return v;
  };
  const auto largestChange = [&](int sources) {
    const auto a = gkpd1(-0.001f, sources), b = gkpd1(0.001f, sources);
    float worst = 0.f;
    for (std::size_t i = 0; i < a.size() && i < b.size(); ++i) worst = std::max(worst, std::abs(a[i] - b[i]));
    return worst;
  };
  EXPECT_GT(largestChange(1), 0.4f * kStep) << "the nearest vertex should switch: the test shows nothing";
  EXPECT_LT(largestChange(4), 0.01f * kStep);
}
