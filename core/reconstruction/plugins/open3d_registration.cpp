// The plugin "open3d"'s registration (src/open3d_plugin.h): pairwise ICP, the pose graph and its
// global optimisation are Open3D's; the joint point-to-plane rounds (all pairs in one least-squares
// problem, over free poses or over the rig's per-camera corrections) are written here, because
// Open3D has no multi-view ICP over a parameterised pose model.
#include <open3d/geometry/KDTreeFlann.h>
#include <open3d/geometry/PointCloud.h>
#include <open3d/pipelines/registration/GlobalOptimization.h>
#include <open3d/pipelines/registration/PoseGraph.h>
#include <open3d/pipelines/registration/Registration.h>
#include <open3d/pipelines/registration/RobustKernel.h>
#include <open3d/pipelines/registration/TransformationEstimation.h>
#include <open3d/utility/Logging.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <memory>
#include <numeric>
#include <optional>
#include <sstream>

#include "../src/open3d_plugin.h"
#include "keyturn/core/median.h"
#include "keyturn/core/plugin.h"

namespace keyturn::reconstruction::detail {

namespace o3g = open3d::geometry;
namespace o3r = open3d::pipelines::registration;

namespace {

struct Failure {
  std::string message;
  int kind;
};

using CloudPtr = std::shared_ptr<o3g::PointCloud>;

// One view at one working resolution: points and normals in the view's own frame, and its tree.
struct Level {
  CloudPtr cloud;
  std::unique_ptr<o3g::KDTreeFlann> tree;
};

Level makeLevel(const o3g::PointCloud& full, double voxel) {
  Level l;
  l.cloud = full.VoxelDownSample(voxel);
  l.cloud->EstimateNormals(o3g::KDTreeSearchParamHybrid(2.5 * voxel, 30));
  l.tree = std::make_unique<o3g::KDTreeFlann>(*l.cloud);
  return l;
}

Eigen::Matrix4d transformOf(const Eigen::Matrix3d& R, const Eigen::Vector3d& t) {
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.topLeftCorner<3, 3>() = R;
  T.topRightCorner<3, 1>() = t;
  return T;
}

// exp of a twist (ω, τ) as a left update: x ↦ R x + t, first order x + ω×x + τ.
Eigen::Matrix4d expTwist(const Eigen::Matrix<double, 6, 1>& xi) {
  const Eigen::Vector3d w = xi.head<3>();
  const double angle = w.norm();
  const Eigen::Matrix3d R =
      angle < 1e-12 ? Eigen::Matrix3d::Identity() : Eigen::AngleAxisd(angle, w / angle).toRotationMatrix();
  return transformOf(R, xi.tail<3>());
}

// Fraction of a's points (posed by Ta) with a point of b (posed by Tb) within `radius`.
double overlapFraction(const Level& a, const Eigen::Matrix4d& Ta, const Level& b, const Eigen::Matrix4d& Tb,
                       double radius) {
  const Eigen::Matrix4d b_from_a = Tb.inverse() * Ta;
  std::vector<int> idx(1);
  std::vector<double> d2(1);
  std::size_t close = 0;
  for (const auto& p : a.cloud->points_) {
    const Eigen::Vector3d q = b_from_a.topLeftCorner<3, 3>() * p + b_from_a.topRightCorner<3, 1>();
    if (b.tree->SearchKNN(q, 1, idx, d2) > 0 && d2[0] <= radius * radius) ++close;
  }
  return a.cloud->points_.empty() ? 0.0 : double(close) / double(a.cloud->points_.size());
}

struct UnionFind {
  std::vector<int> parent;
  explicit UnionFind(int n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int i) { return parent[i] == i ? i : parent[i] = find(parent[i]); }
  bool join(int a, int b) {
    a = find(a), b = find(b);
    if (a == b) return false;
    parent[a] = b;
    return true;
  }
};

// The pairs worth registering: each view's best-overlapping partners (overlap measured both ways,
// the smaller fraction kept), at least min_overlap. Throws Failure when they leave views apart.
std::vector<RegistrationPair> selectPairs(const std::vector<Level>& lv, const std::vector<Eigen::Matrix4d>& poses,
                                          const std::vector<RegistrationView>& views, const RegistrationOptions& o,
                                          double radius, const RegistrationProgress& progress) {
  const int n = int(lv.size());
  // Bounding spheres skip pairs that cannot overlap (144 views: 10 296 pairs).
  std::vector<Eigen::Vector3d> centre(n);
  std::vector<double> extent(n, 0);
  for (int i = 0; i < n; ++i) {
    const auto c = lv[i].cloud->GetCenter();
    centre[i] = poses[i].topLeftCorner<3, 3>() * c + poses[i].topRightCorner<3, 1>();
    for (const auto& p : lv[i].cloud->points_) extent[i] = std::max(extent[i], (p - c).norm());
  }
  std::vector<std::vector<RegistrationPair>> partners(n);
  progress.begin("overlap", std::size_t(n));
  for (int a = 0; a < n; ++a) {
    for (int b = a + 1; b < n; ++b) {
      if ((centre[a] - centre[b]).norm() > extent[a] + extent[b] + radius) continue;
      const double ab = overlapFraction(lv[a], poses[a], lv[b], poses[b], radius);
      // The smaller view's share decides (a small patch on a large scan overlaps it wholly).
      const double ov = std::max(ab, overlapFraction(lv[b], poses[b], lv[a], poses[a], radius));
      if (ov < o.min_overlap) continue;
      partners[a].push_back({a, b, ov});
      partners[b].push_back({a, b, ov});
    }
    progress.step();
  }
  progress.end();
  std::vector<RegistrationPair> pairs;
  for (auto& list : partners) {
    std::sort(list.begin(), list.end(), [](const auto& x, const auto& y) { return x.overlap > y.overlap; });
    if (int(list.size()) > o.max_partners) list.resize(o.max_partners);
    for (const auto& p : list)
      if (std::none_of(pairs.begin(), pairs.end(), [&](const auto& q) { return q.a == p.a && q.b == p.b; }))
        pairs.push_back(p);
  }
  UnionFind uf(n);
  for (const auto& p : pairs) uf.join(p.a, p.b);
  std::vector<std::string> apart;
  for (int i = 0; i < n; ++i)
    if (uf.find(i) != uf.find(o.reference)) apart.push_back(views[i].name);
  if (!apart.empty()) {
    std::ostringstream m;
    m << apart.size() << " of " << n << " views do not overlap the others under their poses (e.g. " << apart[0]
      << "; a pair needs " << int(std::lround(o.min_overlap * 100)) << " % of its points within " << radius * 1000
      << " mm of the other view)";
    throw Failure{m.str(), 2};
  }
  std::sort(pairs.begin(), pairs.end(), [](const auto& x, const auto& y) { return std::tie(x.a, x.b) < std::tie(y.a, y.b); });
  return pairs;
}

// Correspondences of one pair at one distance, accumulated as the joint problem's normal equations
// over the two views' left twists: r = n·(x − q), x = Ta p, q and n of b in the world.
struct Normal {
  Eigen::MatrixXd H;
  Eigen::VectorXd g;
  double cost = 0;
  std::size_t count = 0;
};

void accumulatePair(const Level& a, const Eigen::Matrix4d& Ta, const Level& b, const Eigen::Matrix4d& Tb, int ia,
                    int ib, double max_distance, double huber, Normal& ne) {
  const Eigen::Matrix4d b_from_a = Tb.inverse() * Ta;
  const Eigen::Matrix3d Rb = Tb.topLeftCorner<3, 3>();
  const Eigen::Vector3d tb = Tb.topRightCorner<3, 1>();
  std::vector<int> idx(1);
  std::vector<double> d2(1);
  Eigen::Matrix<double, 12, 12> H = Eigen::Matrix<double, 12, 12>::Zero();
  Eigen::Matrix<double, 12, 1> g = Eigen::Matrix<double, 12, 1>::Zero();
  for (const auto& p : a.cloud->points_) {
    const Eigen::Vector3d pb = b_from_a.topLeftCorner<3, 3>() * p + b_from_a.topRightCorner<3, 1>();
    if (b.tree->SearchKNN(pb, 1, idx, d2) < 1 || d2[0] > max_distance * max_distance) continue;
    const Eigen::Vector3d q = Rb * b.cloud->points_[idx[0]] + tb;
    const Eigen::Vector3d n = Rb * b.cloud->normals_[idx[0]];
    const Eigen::Vector3d x = Rb * pb + tb;
    const double r = n.dot(x - q);
    const double w = std::abs(r) <= huber ? 1.0 : huber / std::abs(r);
    Eigen::Matrix<double, 12, 1> J;
    J << x.cross(n), n, -q.cross(n), -n;
    H.noalias() += w * J * J.transpose();
    g.noalias() += w * r * J;
    ne.cost += w * r * r;
    ++ne.count;
  }
  const int o[2] = {6 * ia, 6 * ib};
  for (int u = 0; u < 2; ++u) {
    ne.g.segment<6>(o[u]) += g.segment<6>(6 * u);
    for (int v = 0; v < 2; ++v) ne.H.block<6, 6>(o[u], o[v]) += H.block<6, 6>(6 * u, 6 * v);
  }
}

// The pose model's linearisation: each view's left twist as a function of the parameters.
// Free: the twists themselves (all views but the reference). Turntable: one right-multiplied
// correction per rig camera, W_i = W_i⁰ · C_k, whose twist maps to view i's left twist through
// the adjoint of W_i.
struct ModelJacobian {
  Eigen::MatrixXd M;  // 6n × parameters
};

Eigen::Matrix<double, 6, 6> adjoint(const Eigen::Matrix4d& T) {
  const Eigen::Matrix3d R = T.topLeftCorner<3, 3>();
  const Eigen::Vector3d t = T.topRightCorner<3, 1>();
  Eigen::Matrix3d tx;
  tx << 0, -t.z(), t.y(), t.z(), 0, -t.x(), -t.y(), t.x(), 0;
  Eigen::Matrix<double, 6, 6> A = Eigen::Matrix<double, 6, 6>::Zero();
  A.topLeftCorner<3, 3>() = R;
  A.bottomRightCorner<3, 3>() = R;
  A.bottomLeftCorner<3, 3>() = tx * R;
  return A;
}

// Joint point-to-plane Gauss–Newton (Levenberg–Marquardt damped) over all pairs at once, at each
// distance of `schedule` for `iterations` steps.
void jointRefine(const std::vector<Level>& lv, const std::vector<RegistrationPair>& pairs,
                 const std::vector<RegistrationView>& views, const RegistrationOptions& o,
                 const std::vector<double>& schedule, int iterations, double huber, std::vector<Eigen::Matrix4d>& poses,
                 std::optional<bool>& turns_kept, const RegistrationProgress& progress) {
  const int n = int(lv.size());
  int cameras = 0;
  for (const auto& v : views) cameras = std::max(cameras, v.rig_camera + 1);
  const bool rig = o.model == PoseModel::Turntable;
  // The parameters: per rig camera its correction's twist; per view otherwise. A camera whose support
  // was levelled moves only as the table lets it: about the turntable's axis (the common z through
  // the origin) and along the table, expressed in the table's frame, so that a symmetric object's free
  // turn about the axis is one parameter of its own (in the camera's frame it mixes with a shift).
  std::vector<int> first(rig ? cameras : 0, -1);
  std::vector<bool> level(rig ? cameras : 0, false);
  for (int i = 0; i < n && rig; ++i) {
    const int k = views[i].rig_camera;
    if (first[k] < 0) first[k] = i;
    if (views[i].support.head<3>().norm() > 0) level[k] = true;
  }
  Eigen::Matrix<double, 6, 3> table_motions = Eigen::Matrix<double, 6, 3>::Zero();  // (ω, v): turn about z, shift x, y
  table_motions(2, 0) = table_motions(3, 1) = table_motions(4, 2) = 1;
  std::vector<int> offset(first.size() + 1, 0);
  for (std::size_t k = 0; k < first.size(); ++k) offset[k + 1] = offset[k] + (level[k] ? 3 : 6);
  const int params = rig ? offset.back() : 6 * n;
  const std::vector<Eigen::Matrix4d> initial = poses;
  std::vector<Eigen::Matrix4d> corrections(rig ? cameras : 0, Eigen::Matrix4d::Identity());
  auto normals = [&](const std::vector<Eigen::Matrix4d>& at, double distance) {
    Normal ne{Eigen::MatrixXd::Zero(6 * n, 6 * n), Eigen::VectorXd::Zero(6 * n)};
    for (const auto& p : pairs) {
      accumulatePair(lv[p.a], at[p.a], lv[p.b], at[p.b], p.a, p.b, distance, huber, ne);
      accumulatePair(lv[p.b], at[p.b], lv[p.a], at[p.a], p.b, p.a, distance, huber, ne);
    }
    return ne;
  };
  // Levelled cameras' turns about the axis are refined only where the object fixes them: where turning
  // one would move the correspondences along their normals by at least `min_turn_information` of a
  // turn that moved every point fully (the points' mean squared distance from the axis per
  // correspondence), on average over the cameras. A body of revolution does not fix the turn between
  // two cameras at all: the tomato can's noise turned one by 1.4°, the plate's by 7°
  // (docs/reconstruction.md). Decided once, at the coarsest level (finer normals carry more of the
  // sensor's noise), and only with two levelled cameras or more: one camera's turn is the gauge.
  double lever2 = 0;
  std::size_t lever_points = 0;
  for (int i = 0; i < n && rig && !turns_kept; ++i)  // only where the decision is still to be made
    for (const auto& p : lv[i].cloud->points_) {
      const Eigen::Vector3d w = poses[i].topLeftCorner<3, 3>() * p + poses[i].topRightCorner<3, 1>();
      lever2 += w.x() * w.x() + w.y() * w.y(), ++lever_points;
    }
  lever2 /= double(std::max<std::size_t>(1, lever_points));

  auto meanCost = [](const Normal& ne) { return ne.count ? ne.cost / double(ne.count) : 1e300; };
  progress.begin("joint refinement", schedule.size() * std::size_t(iterations));
  for (double distance : schedule) {
    Normal ne = normals(poses, distance);
    for (int it = 0; it < iterations; ++it) {
      Eigen::MatrixXd M = Eigen::MatrixXd::Zero(6 * n, params);
      for (int i = 0; i < n; ++i) {
        if (rig) {
          const int k = views[i].rig_camera;
          if (level[k])  // W_i · P⁻¹ exp(ξ) P, P the camera's first view: ξ in the table's frame
            M.block<6, 3>(6 * i, offset[k]) = adjoint(poses[i] * poses[first[k]].inverse()) * table_motions;
          else
            M.block<6, 6>(6 * i, offset[k]) = adjoint(poses[i]);
        }
        else if (i != o.reference)
          M.block<6, 6>(6 * i, 6 * i).setIdentity();
      }
      Eigen::MatrixXd H = M.transpose() * ne.H * M;
      Eigen::VectorXd gp = M.transpose() * ne.g;
      if (!turns_kept) {  // one decision for the object, so that no camera turns against a held one
        double information = 0;
        int levelled = 0;
        for (std::size_t k = 0; k < first.size(); ++k)
          if (level[k]) information += H(offset[k], offset[k]) / (double(ne.count) * lever2), ++levelled;
        turns_kept = levelled >= 2 && information / levelled < o.min_turn_information;
      }
      for (std::size_t k = 0; k < first.size() && *turns_kept; ++k) {
        const int t = offset[k];  // the turn's parameter
        if (level[k]) H.row(t).setZero(), H.col(t).setZero(), H(t, t) = 1, gp(t) = 0;
      }
      // Levenberg–Marquardt: a step is kept only when the mean robust cost at the new poses'
      // correspondences falls without losing correspondences; else a larger λ (shorter step). The
      // smallest λ also holds the gauge (the reference's parameters, or the rotation about and the
      // shift along a turntable's axis), which has no curvature.
      bool accepted = false;
      for (double factor : {1e-6, 1e-4, 1e-2, 1.0}) {
        Eigen::MatrixXd Hp = H;
        Hp.diagonal().array() += factor * std::max(1e-12, H.diagonal().maxCoeff());
        const Eigen::VectorXd dp = -Hp.ldlt().solve(gp);
        if (!dp.allFinite()) break;
        std::vector<Eigen::Matrix4d> candidate = poses, candidate_corrections = corrections;
        if (rig) {
          for (int k = 0; k < cameras; ++k)
            candidate_corrections[k] =
                level[k] ? Eigen::Matrix4d(corrections[k] * poses[first[k]].inverse() *
                                           expTwist(table_motions * dp.segment<3>(offset[k])) * poses[first[k]])
                         : Eigen::Matrix4d(corrections[k] * expTwist(dp.segment<6>(offset[k])));
          for (int i = 0; i < n; ++i) candidate[i] = initial[i] * candidate_corrections[views[i].rig_camera];
        } else {
          for (int i = 0; i < n; ++i) candidate[i] = expTwist(M.block(6 * i, 0, 6, params) * dp) * poses[i];
        }
        Normal next = normals(candidate, distance);
        if (meanCost(next) < meanCost(ne) && double(next.count) >= 0.9 * double(ne.count)) {
          poses = std::move(candidate), corrections = std::move(candidate_corrections), ne = std::move(next);
          accepted = true;
          break;
        }
      }
      progress.step();
      if (!accepted) break;
    }
  }
  progress.end();
  if (rig) {  // keep the reference view where it was: move the whole set, the gauge
    const Eigen::Matrix4d G = initial[o.reference] * poses[o.reference].inverse();
    for (auto& T : poses) T = G * T;
  }
}

// Per view: the median point-to-plane distance of its points to its partners, over the points
// that have a partner point within `radius`, and the fraction that have one.
void measureResiduals(const std::vector<Level>& lv, const std::vector<RegistrationPair>& pairs,
                      const std::vector<Eigen::Matrix4d>& poses, double radius, std::vector<double>& residual,
                      std::vector<double>& overlap) {
  const int n = int(lv.size());
  residual.assign(n, std::nan(""));
  overlap.assign(n, 0);
  std::vector<std::vector<int>> partners(n);
  for (const auto& p : pairs) partners[p.a].push_back(p.b), partners[p.b].push_back(p.a);
  std::vector<int> idx(1);
  std::vector<double> d2(1);
  for (int a = 0; a < n; ++a) {
    std::vector<double> best(lv[a].cloud->points_.size(), std::numeric_limits<double>::infinity());
    std::vector<double> plane(best.size(), 0);
    for (int b : partners[a]) {
      const Eigen::Matrix4d b_from_a = poses[b].inverse() * poses[a];
      for (std::size_t k = 0; k < best.size(); ++k) {
        const Eigen::Vector3d pb =
            b_from_a.topLeftCorner<3, 3>() * lv[a].cloud->points_[k] + b_from_a.topRightCorner<3, 1>();
        if (lv[b].tree->SearchKNN(pb, 1, idx, d2) < 1 || d2[0] >= best[k]) continue;
        best[k] = d2[0];
        plane[k] = std::abs(lv[b].cloud->normals_[idx[0]].dot(pb - lv[b].cloud->points_[idx[0]]));
      }
    }
    std::vector<double> close;
    for (std::size_t k = 0; k < best.size(); ++k)
      if (best[k] <= radius * radius) close.push_back(plane[k]);
    if (close.empty()) continue;
    residual[a] = upperMedian(close);
    overlap[a] = double(close.size()) / double(best.size());
  }
}

// Pairwise point-to-plane ICP, coarse to fine, from the current relative pose: b ← a.
o3r::RegistrationResult pairwiseIcp(const std::vector<std::vector<Level>>& levels, int a, int b,
                                    const Eigen::Matrix4d& b_from_a, const std::vector<double>& distances) {
  // Tukey's loss at each level's distance: points of the other view's non-overlapping part, met
  // at the edge of the search, do not drag the pair. A level that loses most of the previous
  // level's matches has slid off (a small patch on a smooth surface): the pair keeps the pose it had.
  Eigen::Matrix4d T = b_from_a;
  o3r::RegistrationResult r(T);
  double previous = -1;
  for (std::size_t l = 0; l < distances.size(); ++l) {
    // The last distances use the finest levels (a fine-only round starts at level size − count).
    const std::size_t li = levels[a].size() >= distances.size() ? levels[a].size() - distances.size() + l
                                                                : std::min(l, levels[a].size() - 1);
    const auto before = o3r::EvaluateRegistration(*levels[a][li].cloud, *levels[b][li].cloud, distances[l], T);
    const auto step = o3r::RegistrationICP(
        *levels[a][li].cloud, *levels[b][li].cloud, distances[l], T,
        o3r::TransformationEstimationPointToPlane(std::make_shared<o3r::TukeyLoss>(distances[l])),
        o3r::ICPConvergenceCriteria(1e-7, 1e-7, 50));
    if (step.fitness_ < 0.5 * before.fitness_ || (previous > 0 && step.fitness_ < 0.5 * previous)) {
      r = before;
      break;
    }
    r = step;
    T = r.transformation_;
    previous = r.fitness_;
  }
  return r;
}

// Pairwise ICP of every pair into a pose graph (edges of a maximum spanning tree of ICP fitness
// certain, the others loop closures the line process may prune), then the global optimisation.
void poseGraphRound(const std::vector<std::vector<Level>>& levels, std::vector<RegistrationPair>& pairs,
                    const std::vector<double>& distances, double voxel, int reference,
                    std::vector<Eigen::Matrix4d>& poses, const RegistrationProgress& progress) {
  const int n = int(poses.size());
  struct Edge {
    int a, b;
    Eigen::Matrix4d T;
    Eigen::Matrix6d info;
    double fitness;
  };
  std::vector<Edge> edges;
  progress.begin("pairwise ICP", pairs.size());
  for (auto& p : pairs) {
    const auto r = pairwiseIcp(levels, p.a, p.b, poses[p.b].inverse() * poses[p.a], distances);
    const auto& fine = levels[p.a].back();
    const auto info = o3r::GetInformationMatrixFromPointClouds(*fine.cloud, *levels[p.b].back().cloud,
                                                               distances.back(), r.transformation_);
    p.fitness = r.fitness_;
    edges.push_back({p.a, p.b, r.transformation_, info, r.fitness_});
    progress.step();
  }
  progress.end();
  std::vector<int> order(edges.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int x, int y) { return edges[x].fitness > edges[y].fitness; });
  UnionFind tree(n);
  std::vector<bool> certain(edges.size(), false);
  for (int e : order) certain[e] = tree.join(edges[e].a, edges[e].b);
  o3r::PoseGraph graph;
  for (const auto& T : poses) graph.nodes_.emplace_back(T);
  for (std::size_t e = 0; e < edges.size(); ++e)
    graph.edges_.emplace_back(edges[e].a, edges[e].b, edges[e].T, edges[e].info, !certain[e]);
  progress.begin("pose graph", 1);
  o3r::GlobalOptimization(graph, o3r::GlobalOptimizationLevenbergMarquardt(),
                          o3r::GlobalOptimizationConvergenceCriteria(),
                          o3r::GlobalOptimizationOption(distances.back(), 0.25, 1.0, reference));
  progress.step();
  progress.end();
  // Open3D leaves the reference node at the identity, not at its pose: move the set back onto it.
  const Eigen::Matrix4d G = poses[reference] * graph.nodes_[reference].pose_.inverse();
  for (int i = 0; i < n; ++i) poses[i] = G * graph.nodes_[i].pose_;
  for (auto& p : pairs)
    p.pruned = std::none_of(graph.edges_.begin(), graph.edges_.end(), [&](const o3r::PoseGraphEdge& e) {
      return e.source_node_id_ == p.a && e.target_node_id_ == p.b;
    });
  (void)voxel;
}

RegistrationResult registerAll(const std::vector<RegistrationView>& views, const RegistrationOptions& o,
                               const RegistrationProgress& progress) {
  const int n = int(views.size());
  if (n < 2) throw Failure{"a reconstruction needs at least two views, got " + std::to_string(n), 1};
  if (o.reference < 0 || o.reference >= n) throw Failure{"the reference view is not one of the views", 1};
  std::vector<o3g::PointCloud> full(n);
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e30), hi = -lo;
  for (int i = 0; i < n; ++i) {
    if (views[i].points.size() < 100)
      throw Failure{views[i].name + ": " + std::to_string(views[i].points.size()) + " valid points, a view needs 100", 1};
    full[i].points_.reserve(views[i].points.size());
    for (const auto& p : views[i].points) full[i].points_.push_back(p.cast<double>());
    const auto& T = views[i].world_from_view;
    for (const auto& p : full[i].points_) {
      const Eigen::Vector3d w = T.topLeftCorner<3, 3>() * p + T.topRightCorner<3, 1>();
      lo = lo.cwiseMin(w), hi = hi.cwiseMax(w);
    }
  }
  RegistrationResult res;
  // Auto: 1/250 of the object, but no finer than the views' own point spacing (median distance to
  // the nearest neighbour over a sample of each view): an SR4000 view has a point every ~2 mm, and
  // correspondences finer than that only see its noise.
  double voxel = o.voxel_m;
  if (voxel <= 0) {
    std::vector<double> spacing;
    std::vector<int> idx(2);
    std::vector<double> d2(2);
    for (const auto& f : full) {
      const o3g::KDTreeFlann tree(f);
      const std::size_t stride = std::max<std::size_t>(1, f.points_.size() / 200);
      for (std::size_t k = 0; k < f.points_.size(); k += stride)
        if (tree.SearchKNN(f.points_[k], 2, idx, d2) == 2) spacing.push_back(std::sqrt(d2[1]));
    }
    voxel = std::max((hi - lo).norm() / 250.0, upperMedian(spacing));
  }
  res.voxel_m = voxel;
  // The first correspondence distance covers the poses' expected error: 1/20 of the object (a
  // 2° / 5 mm error moves a bunny's points ≤ 9 mm), between 3 and 12 voxels; the levels' voxels
  // follow it down to the finest.
  const double initial = o.initial_distance_m > 0 ? o.initial_distance_m
                                                  : std::clamp((hi - lo).norm() / 20.0, 3 * voxel, 12 * voxel);
  const std::vector<double> level_voxels{std::max(voxel, initial / 3), std::max(voxel, initial / 6), voxel};
  const std::vector<double> distances{initial, std::max(initial / 3, 3 * voxel), 1.5 * voxel};
  std::vector<std::vector<Level>> levels(n);
  progress.begin("views", std::size_t(n));
  for (int i = 0; i < n; ++i) {
    for (double v : level_voxels) levels[i].push_back(makeLevel(full[i], v));
    progress.step();
  }
  progress.end();
  std::vector<Level> coarse(n), fine(n);
  for (int i = 0; i < n; ++i) {
    coarse[i].cloud = levels[i][0].cloud, coarse[i].tree = std::make_unique<o3g::KDTreeFlann>(*coarse[i].cloud);
    fine[i].cloud = levels[i].back().cloud, fine[i].tree = std::make_unique<o3g::KDTreeFlann>(*fine[i].cloud);
  }
  std::vector<Eigen::Matrix4d> poses(n);
  for (int i = 0; i < n; ++i) poses[i] = views[i].world_from_view;
  res.pairs = selectPairs(coarse, poses, views, o, initial / 2, progress);
  const double measure_radius = 3 * voxel;
  measureResiduals(fine, res.pairs, poses, initial, res.residual_before_m, res.overlap_before);
  if (o.refine) {
    if (o.model == PoseModel::Free) {
      poseGraphRound(levels, res.pairs, distances, voxel, o.reference, poses, progress);
      // Joint rounds: every pair re-registered from the optimised poses at the fine distances, and
      // the graph optimised again. (A joint point-to-plane least squares over all pairs at once,
      // as the turntable model uses, moved the bunny's poses further from bun.conf: 0.234° median
      // against 0.201° without it.)
      for (int round = 0; round < o.joint_rounds; ++round)
        poseGraphRound(levels, res.pairs, {3 * voxel, 1.5 * voxel}, voxel, o.reference, poses, progress);
    } else {
      // The rig has few parameters: the joint problem converges from the calibrated poses without
      // a pose graph, coarse to fine.
      for (int i = 0; i < n; ++i) poses[i] = poses[i] * views[i].level;
      std::vector<Level>& mid = coarse;
      std::vector<double> sched{initial, std::max(initial / 3, 3 * voxel)};
      std::optional<bool> turns_kept;
      jointRefine(mid, res.pairs, views, o, sched, 4, voxel, poses, turns_kept, progress);
      jointRefine(fine, res.pairs, views, o, {3 * voxel, 1.5 * voxel}, std::max(2, o.joint_rounds), voxel, poses,
                  turns_kept, progress);
      res.turns_kept = turns_kept.value_or(false);
    }
  }
  measureResiduals(fine, res.pairs, poses, measure_radius > initial ? measure_radius : initial, res.residual_after_m,
                   res.overlap_after);
  res.world_from_view = poses;
  return res;
}

std::string registerEntry(const std::vector<RegistrationView>& views, const RegistrationOptions& options,
                          const RegistrationProgress& progress, RegistrationResult& result, int& error_kind) {
  open3d::utility::SetVerbosityLevel(open3d::utility::VerbosityLevel::Error);
  try {
    result = registerAll(views, options, progress);
    error_kind = 0;
    return "";
  } catch (const Failure& f) {
    error_kind = f.kind;
    return f.message;
  } catch (const std::exception& e) {
    error_kind = 1;
    return std::string("Open3D: ") + e.what();
  }
}

}  // namespace

// Defined in open3d_surface.cpp.
std::string fuseEntry(const std::vector<FuseView>& views, const FuseOptions& options, OrientedPoints& out);
std::string poissonEntry(const OrientedPoints& cloud, const PoissonOptions& options, Mesh& out);
std::string loadMeshEntry(const std::string& path, Mesh& out);
std::string distancesEntry(const std::vector<Eigen::Vector3f>& points, const Mesh& reference, std::vector<double>& out);
std::string sampleEntry(const Mesh& mesh, std::size_t samples, std::vector<Eigen::Vector3f>& out);
std::string tsdfEntry(const std::vector<DepthFrame>& frames, const OrientedPoints& points, const TsdfOptions& options,
                      Mesh& out);

}  // namespace keyturn::reconstruction::detail

KEYTURN_PLUGIN_EXPORT const keyturn::reconstruction::detail::Open3dFunctions* keyturn_open3d() {
  using namespace keyturn::reconstruction::detail;
  static const Open3dFunctions table{registerEntry, fuseEntry, poissonEntry, loadMeshEntry, distancesEntry, sampleEntry,
                                    tsdfEntry};
  return &table;
}
