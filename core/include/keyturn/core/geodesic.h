#pragma once
// Geodesic keypoint functions (§4.3, §4.6) on the paper's "local complete
// graph": each point is joined to every neighbour within r, and those neighbours
// to each other. Equivalently an edge (j,k) exists when some point lies within r
// of both, so the adjacency of j is its 2-hop neighbourhood in the r-ball graph.
#include <Eigen/Core>
#include <vector>

#include "keyturn/core/cloud.h"
#include "keyturn/core/radius_search.h"

namespace keyturn {

struct GraphOptions {
  double radius = 3.5;               // multiples of the cloud resolution
  double curvature_epsilon = 1e-4;   // floor of the curvature factor C for coplanar normals
  // Normals and curvature-weighted costs are only needed for GKPCD2; without
  // them the graph builds faster (describeView leaves them out when not asked for).
  bool curvature_weights = true;
  // Edges of the local complete graph longer than r (the 2-hop ones) are left out when
  // a path through one of their common neighbours is at most this much longer: every
  // graph distance then lies within [d, (1 + tolerance) d] of the exact graph's, and
  // Dijkstra scans about a quarter of the edges. 0 = the exact graph.
  double shortcut_tolerance = 0.01;
  // GKPCD2's graph leaves out every edge that a two-edge path through a common neighbour
  // undercuts in curved cost: such an edge lies on no cheapest path, so the cheapest paths
  // are those of the whole edge set. false keeps every edge (tests compare the two).
  bool curved_dominance_pruning = true;
  // GKPD1's source: the centroid lies off the surface, and the one vertex nearest it changes when
  // the view moves by less than the vertex spacing, shifting every GKPD1 value by up to a spacing.
  // With m > 1 a keypoint's GKPD1 is the blend of its distances from the centroid's m nearest
  // vertices, each weighted by how much nearer it is than the (m+1)-th: a vertex enters or leaves
  // the blend at weight 0, so GKPD1 changes continuously with the view. 1 = the nearest vertex alone.
  int centroid_sources = 1;
};

// Compressed adjacency (CSR) with Euclidean edge lengths, and GKPCD2's curvature-weighted
// graph over the same vertices in its own CSR (a subset of the edges, see GraphOptions).
struct LocalCompleteGraph {
  std::vector<int> offsets;       // size n+1
  std::vector<int> targets;
  std::vector<float> length;      // Euclidean edge length L
  // Empty without curvature weights:
  std::vector<int> curved_offsets, curved_targets;
  std::vector<float> curved_cost;    // max(C, ε) · L, C = sin(arccos(n_i·n_j))
  std::vector<float> curved_length;  // L of the same edge
  std::vector<Eigen::Vector3f> normals;  // PCA normal per vertex (NaN when undefined)
  std::size_t vertexCount() const { return offsets.empty() ? 0 : offsets.size() - 1; }
  std::size_t edgeCount() const { return targets.size() / 2; }
  std::size_t curvedEdgeCount() const { return curved_targets.size() / 2; }
  bool hasCurvedGraph() const { return curved_offsets.size() == offsets.size() && !offsets.empty(); }
};

LocalCompleteGraph buildLocalCompleteGraph(const PointSet& set, const RadiusSearch& search,
                                           double resolution, const GraphOptions& options);

struct GeodesicResult {
  std::vector<float> gkpd1;   // centroid's source vertices → each reachable keypoint
  std::vector<float> gkpd2;   // each reachable keypoint pair (graph distance)
  std::vector<float> gkpcd2;  // Euclidean length of each pair's curvature-weighted path
  // With keypoint weights: each value's weight (w of its keypoint, w_a·w_b of its pair), in the same order.
  std::vector<float> gkpd1_weight, gkpd2_weight, gkpcd2_weight;
  int centroid_vertex = -1;
  int unreachable_from_centroid = 0;  // keypoints in another connected component
  int unreachable_pairs = 0;
};

enum GeodesicSet { kGkpd1 = 1, kGkpd2 = 2, kGkpcd2 = 4, kAllGeodesics = 7 };

// keypoints index the graph's vertices. Unreachable keypoints are counted,
// never put into a histogram as infinity.
// weights, when given, one per keypoint (the weighted budget, iss.h): the result also holds each
// value's weight. centroid_sources: GraphOptions::centroid_sources.
GeodesicResult geodesicKeypointDistances(const LocalCompleteGraph& graph, const PointSet& set,
                                         const std::vector<int>& keypoints,
                                         int which = kAllGeodesics, const std::vector<double>* weights = nullptr,
                                         int centroid_sources = 1);

// Single-source shortest paths (all vertices), exposed for tests and plots.
// With curvature=true the path minimises the curved cost and the returned
// value is the Euclidean length of that path.
std::vector<float> shortestPathLengths(const LocalCompleteGraph& graph, int source, bool curvature);

// The shortest paths (Euclidean edge costs) from `source` to each target, as
// vertex sequences source … target; an unreachable target gets an empty path.
// For showing a view's geodesics, e.g. GKPD1's centroid → keypoint paths.
std::vector<std::vector<int>> shortestPaths(const LocalCompleteGraph& graph, int source,
                                            const std::vector<int>& targets);

// The graph vertex nearest the set's centroid: where GKPD1's paths start.
int centroidVertex(const PointSet& set);

// GKPD1's sources (GraphOptions::centroid_sources): the m vertices nearest the set's centroid,
// nearest first, with blend weights summing to 1 (d_{m+1} − d_i, equal when those are all 0).
struct CentroidSources {
  std::vector<int> vertex;
  std::vector<double> weight;
};
CentroidSources centroidSources(const PointSet& set, int m);

// For display: the GKPD1 paths of a view on its graph (the one the descriptor built), from the
// vertex nearest the centroid to each reachable keypoint (indices into `set`), as polylines.
std::vector<std::vector<Eigen::Vector3f>> centroidGeodesicPolylines(const LocalCompleteGraph& graph, const PointSet& set,
                                                                    const std::vector<int>& keypoints);

namespace detail {
// The searches relax edges eight at a time with AVX2 where the CPU has it, with results
// bit-identical to the scalar loop; true forces the scalar loop (tests and benchmarks compare them).
void useScalarGeodesics(bool scalar);
// Whether the searches take the AVX2 path now (the CPU has AVX2 and it is not switched off).
bool geodesicsUseAvx2();
}  // namespace detail

}  // namespace keyturn
