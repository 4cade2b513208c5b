// A reduced simulated reconstruction (issue 50): 8 SR4000 views of the shipped YCB drill around the
// turntable at 30° elevation, the rig's axis calibration mis-set by 2° and 5 mm. With refinement
// the poses and the surface come back; without it they do not (both asserted).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <filesystem>

#include "keyturn/core/cloud_io.h"
#include "keyturn/core/error.h"
#include "keyturn/core/pose_list.h"
#include "keyturn/reconstruction/reconstruction.h"
#include "keyturn/reconstruction/support.h"
#include "keyturn/sim/mesh.h"
#include "keyturn/sim/tof_view.h"
#include "support/scratch_path.h"

using namespace keyturn;
using namespace keyturn::reconstruction;
namespace fs = std::filesystem;

namespace {

double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

Eigen::Matrix4d rz(double deg) {
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.topLeftCorner<3, 3>() = Eigen::AngleAxisd(deg * M_PI / 180, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return T;
}

// A simulated SR4000 view of `mesh` on the turntable, saved as `file`, with its true pose.
PosedView renderedView(sim::TofViewRenderer& renderer, const sim::Mesh& mesh, const sim::SceneView& v,
                       const std::string& file, const std::string& object) {
  PosedView pv;
  pv.file = file;
  saveCloud(pv.file, renderer.render(v));
  pv.object = object;
  pv.elevation = std::to_string(int(v.elevation_deg));
  pv.angle_deg = v.turntable_deg;
  pv.turntable = true;
  pv.world_from_view = (sim::cameraFromTurntable(mesh, v) * rz(v.turntable_deg)).inverse();
  return pv;
}

struct SimulatedTurn {
  sim::Mesh mesh;
  std::vector<PosedView> views;           // with the mis-set axis
  std::vector<Eigen::Matrix4d> truth;     // world (the mug's frame) from view
};

// Rendered once for the suite: the views, their true poses, and the poses a calibration 2° and
// 5 mm off gives (the camera's pose on the table wrong by that much, the same for every view).
const SimulatedTurn& turn() {
  static const SimulatedTurn t = [] {
    SimulatedTurn s;
    s.mesh = sim::loadMesh(std::string(KEYTURN_DATA_DIR) + "/objects/drill__ycb_035_power_drill.ply");
    sim::TofViewRenderer renderer(s.mesh);
    // The suite's views, removed when the process ends.
    static const keyturn::test::ScratchFolder folder("reconstruction_test");
    const std::string dir = folder.made().string();
    Eigen::Matrix4d miss = Eigen::Matrix4d::Identity();
    miss.topLeftCorner<3, 3>() = Eigen::AngleAxisd(2 * M_PI / 180, Eigen::Vector3d(1, 1, 0).normalized()).toRotationMatrix();
    miss.topRightCorner<3, 1>() = Eigen::Vector3d(0.003, -0.004, 0);  // 5 mm
    for (int k = 0; k < 8; ++k) {
      sim::SceneView v;
      v.turntable_deg = 45.0 * k;
      v.seed = 7 + k;
      const Eigen::Matrix4d camera_from_table = sim::cameraFromTurntable(s.mesh, v);
      PosedView pv;
      pv.file = dir + "/view" + std::to_string(k) + ".pcd";
      saveCloud(pv.file, renderer.render(v));
      pv.object = "drill/ycb";
      pv.elevation = "30";
      pv.angle_deg = v.turntable_deg;
      pv.turntable = true;
      s.truth.push_back((camera_from_table * rz(v.turntable_deg)).inverse());
      pv.world_from_view = (camera_from_table * miss * rz(v.turntable_deg)).inverse();
      s.views.push_back(pv);
    }
    return s;
  }();
  return t;
}

Mesh asMesh(const sim::Mesh& m) { return {m.vertices, m.triangles}; }

struct Outcome {
  double rotation_deg = 0, translation_m = 0;  // worst view, relative to view 0 (the gauge)
  double surface_m = 0;                        // fused points to the true mesh, median
  bool turns_kept = false;
};

Outcome run(bool refine) {
  ReconstructionOptions o;
  o.registration.refine = refine;
  o.poisson.depth = 7;
  const auto r = reconstruct(turn().views, o);
  EXPECT_EQ(r.model, PoseModel::Turntable);
  // Both sets in the true frame through view 0 (its pose is the gauge both keep).
  const Eigen::Matrix4d G = turn().truth[0] * r.views[0].world_from_view.inverse();
  Outcome out;
  for (std::size_t i = 1; i < r.views.size(); ++i) {
    const auto d = poseDifference(turn().truth[i], G * r.views[i].world_from_view);
    out.rotation_deg = std::max(out.rotation_deg, d.rotation_deg);
    out.translation_m = std::max(out.translation_m, d.translation_m);
  }
  std::vector<Eigen::Vector3f> pts;
  for (const auto& p : r.cloud.points) pts.push_back((G.cast<float>() * p.homogeneous()).head<3>());
  out.surface_m = median(distancesToMesh(pts, asMesh(turn().mesh)));
  out.turns_kept = r.turns_kept;
  return out;
}

}  // namespace

TEST(Reconstruction, MisSetAxisIsRecoveredByTheRigModel) {
  const Outcome o = run(true);
  EXPECT_LT(o.rotation_deg, 0.3);
  EXPECT_LT(o.translation_m, 0.0015);
  EXPECT_LT(o.surface_m, 0.002);  // SR4000 noise: the 2 mm
  EXPECT_FALSE(o.turns_kept);     // the drill fixes its turn about the axis (one camera: the gauge)
}

TEST(Reconstruction, WithoutRefinementTheMisSetAxisStays) {
  const Outcome o = run(false);
  EXPECT_GT(o.rotation_deg, 1.0);
  EXPECT_GT(o.translation_m, 0.003);
  EXPECT_GT(o.surface_m, 0.002);
}

// A body of revolution (the YCB tomato soup can) from two rig cameras, 30° and 45°, 8 views each,
// both cameras' axis calibration mis-set by 2° and 5 mm (missetAxis, seed 1). The object alone fixes
// neither camera's tilt well nor their turn about the axis relative to each other: refined freely (each
// camera's six degrees of freedom, the rig model before) the cameras came back 1.4° apart about the
// axis on 72 views, and 0.58° / 4.4 mm off on these 16. Levelled on the support plane, with the turn
// held where the can does not fix it, every view comes back within the 0.2° / 1 mm (0.027° /
// 0.85 mm).
struct SymmetricOutcome {
  double rotation_deg = 0, translation_m = 0;  // worst view, through the reference view
  std::vector<AxisReport> axes;
  bool turns_kept = false;
};

SymmetricOutcome symmetricTurn(bool level_on_support) {
  static const keyturn::test::ScratchFolder folder("reconstruction_symmetric");
  static const auto views = [] {
    const sim::Mesh mesh = sim::loadMesh(std::string(KEYTURN_DATA_DIR) + "/objects/can__ycb_005_tomato_soup_can.ply");
    sim::TofViewRenderer renderer(mesh);
    std::vector<PosedView> out;
    for (int e : {30, 45})
      for (int k = 0; k < 8; ++k) {
        sim::SceneView v;
        v.elevation_deg = e;
        v.turntable_deg = 45.0 * k;
        v.seed = 200 + e + k;
        const auto file = folder.made() / ("e" + std::to_string(e) + "_" + std::to_string(k) + ".pcd");
        out.push_back(renderedView(renderer, mesh, v, file.string(), "can/ycb"));
      }
    return out;
  }();
  ReconstructionOptions o;
  o.poisson.depth = 6;
  o.registration.level_on_support = level_on_support;
  for (const auto& v : views) o.reference_poses.push_back(v.world_from_view);
  auto missed = views;
  missetAxis(missed, 2, 0.005, 1);
  const auto r = reconstruct(missed, o);
  SymmetricOutcome out;
  for (const auto& v : r.outcomes) {
    out.rotation_deg = std::max(out.rotation_deg, v.error_after->rotation_deg);
    out.translation_m = std::max(out.translation_m, v.error_after->translation_m);
  }
  out.axes = r.axes;
  out.turns_kept = r.turns_kept;
  return out;
}

TEST(Reconstruction, ASymmetricObjectsMisSetAxisComesBackLevelledOnTheSupport) {
  const auto o = symmetricTurn(true);
  EXPECT_LT(o.rotation_deg, 0.2);
  EXPECT_LT(o.translation_m, 0.001);
  EXPECT_TRUE(o.turns_kept);  // the can does not fix the cameras' turns about the axis
  ASSERT_EQ(o.axes.size(), 2u);
  for (const auto& a : o.axes) {
    ASSERT_TRUE(a.levelled_deg.has_value()) << a.camera;
    EXPECT_NEAR(*a.levelled_deg, 2.0, 0.1) << a.camera;  // the mis-set tilt, found from the table alone
  }
}

TEST(Reconstruction, ASymmetricObjectsMisSetAxisStaysWhenTheTiltIsRefinedFreely) {
  const auto o = symmetricTurn(false);
  EXPECT_GT(o.rotation_deg, 0.3);      // measured 0.58° (levelled: 0.027°)
  EXPECT_GT(o.translation_m, 0.002);   // measured 4.4 mm (levelled: 0.85 mm)
  for (const auto& a : o.axes) EXPECT_FALSE(a.levelled_deg.has_value()) << a.camera;
}

// levelRigOnSupport on planes worked by hand. The table is z = 0 in the table's frame; a view's pose is
// rz(−θ)·X, X the camera's pose on the table (as in turn()). Camera 0's calibration is tilted 3° about
// x and lifted 4 mm, camera 1's only lifted 4 mm: both are levelled at 4 mm, and camera 0's tilt of 3°
// found. Camera 2's three views see three different planes, camera 3 found one in one view of three:
// neither is levelled, and their poses are kept.
TEST(Reconstruction, EachRigCamerasSupportIsLevelledAtOneHeight) {
  const auto onTable = [](double camera_deg) {  // 0.7 m from the axis, looking at it from `camera_deg` up
    Eigen::Matrix4d X = Eigen::Matrix4d::Identity();
    X.topLeftCorner<3, 3>() = Eigen::AngleAxisd(-(90 + camera_deg) * M_PI / 180, Eigen::Vector3d::UnitX()).toRotationMatrix();
    X.topRightCorner<3, 1>() =
        Eigen::Vector3d(0, -0.7 * std::cos(camera_deg * M_PI / 180), 0.7 * std::sin(camera_deg * M_PI / 180));
    return X;
  };
  const auto error = [](double tilt_deg, double lift_m) {
    Eigen::Matrix4d E = Eigen::Matrix4d::Identity();
    E.topLeftCorner<3, 3>() = Eigen::AngleAxisd(tilt_deg * M_PI / 180, Eigen::Vector3d::UnitX()).toRotationMatrix();
    E(2, 3) = lift_m;
    return E;
  };
  const auto planeSeen = [](const Eigen::Matrix4d& X, const Eigen::Vector3d& n) {
    // n·w = 0 with w = R x + t: (Rᵀn)·x + n·t = 0, its normal towards the camera (n·t > 0)
    const Eigen::Vector3d v = X.topLeftCorner<3, 3>().transpose() * n;
    return Eigen::Vector4f(Eigen::Vector4d(v.x(), v.y(), v.z(), n.dot(X.topRightCorner<3, 1>())).cast<float>());
  };
  const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d tilted_x(0, std::sin(10 * M_PI / 180), std::cos(10 * M_PI / 180));
  const Eigen::Vector3d tilted_y(std::sin(10 * M_PI / 180), 0, std::cos(10 * M_PI / 180));
  const Eigen::Matrix4d X30 = onTable(30), X45 = onTable(45);
  std::vector<SupportView> views;
  std::vector<int> camera;
  for (int a = 0; a < 3; ++a) {
    const Eigen::Matrix4d turn = rz(-60.0 * a);
    views.push_back({true, planeSeen(X30, up), 0.003f, turn * error(3, 0.004) * X30});
    views.push_back({true, planeSeen(X45, up), 0.003f, turn * error(0, 0.004) * X45});
    views.push_back({true, planeSeen(X45, a == 0 ? up : a == 1 ? tilted_x : tilted_y), 0.003f, turn * X45});
    views.push_back({a == 0, planeSeen(X45, up), 0.003f, turn * X45});
    camera.insert(camera.end(), {0, 1, 2, 3});
  }
  const auto r = levelRigOnSupport(views, camera);
  ASSERT_EQ(r.camera_plane.size(), 4u);
  EXPECT_TRUE(r.camera_plane[0] && r.camera_plane[1]);
  EXPECT_FALSE(r.camera_plane[2]);
  EXPECT_FALSE(r.camera_plane[3]);
  EXPECT_NEAR(r.tilt_deg[0], 3.0, 1e-4);
  EXPECT_NEAR(r.tilt_deg[1], 0.0, 1e-4);
  EXPECT_NEAR(r.height_m, 0.004, 1e-6);
  for (std::size_t i = 0; i < views.size(); ++i) {
    const Eigen::Matrix4d& W = r.world_from_view[i];
    if (camera[i] > 1) {
      EXPECT_TRUE(W.isApprox(views[i].world_from_view)) << i;
      continue;
    }
    // The view's plane in the common frame is level (z up) at 4 mm.
    const Eigen::Vector4d p = views[i].plane.cast<double>();
    const Eigen::Vector3d n = W.topLeftCorner<3, 3>() * p.head<3>();
    EXPECT_NEAR(n.z(), 1.0, 1e-6) << i;
    EXPECT_NEAR(n.dot(W.topRightCorner<3, 1>()) - p[3], 0.004, 1e-6) << i;
  }
}

// A thin object on the table (issue 50): 12 SR4000 views of the YCB scissors (96 × 202 × 16 mm) at
// 30° and 45°, on their true poses. The filter's fixed 8 mm support band took the lower half of
// every view, and Poisson bulged past the sparse points: the surface was 167 × 228 × 26 mm, its
// foot 5 mm above the table. Now the band follows each frame's table noise, the foot is closed on
// the support and the surface is kept near the points: its box within 5 mm of the true one.
TEST(Reconstruction, ThinObjectOnTheTableKeepsItsSize) {
  const sim::Mesh mesh = sim::loadMesh(std::string(KEYTURN_DATA_DIR) + "/objects/scissors__ycb_037_scissors.ply");
  sim::TofViewRenderer renderer(mesh);
  const keyturn::test::ScratchFolder folder("reconstruction_thin");
  const std::string dir = folder.made().string();
  std::vector<PosedView> views;
  for (int e : {30, 45})
    for (int k = 0; k < 6; ++k) {
      sim::SceneView v;
      v.elevation_deg = e;
      v.turntable_deg = 60.0 * k + (e == 45 ? 30 : 0);
      v.seed = 100 + e + k;
      views.push_back(renderedView(renderer, mesh, v, dir + "/e" + std::to_string(e) + "_" + std::to_string(k) + ".pcd",
                                   "scissors/ycb"));
    }
  // Poisson closes the foot on the support; a TSDF ends where the frames' points do, which the
  // support band's regrowth brings to within 3 σ of the table's noise (about 3 mm on the SR4000).
  for (const auto& [surface, foot_m] : {std::pair{SurfaceChoice::Poisson, 0.002}, std::pair{SurfaceChoice::Tsdf, 0.003}}) {
    SCOPED_TRACE(surface == SurfaceChoice::Tsdf ? "TSDF" : "Poisson");
    ReconstructionOptions o;
    o.registration.refine = false;  // the surface on true poses: what the filter and the surface make of them
    o.surface = surface;
    o.poisson.depth = 8;
    const auto r = reconstruct(views, o);
    EXPECT_EQ(r.surface, surface);
    ASSERT_TRUE(r.support.has_value());
    EXPECT_NEAR(r.support->z(), 1.0, 1e-3);  // the table, z up
    EXPECT_NEAR((*r.support)[3], 0.0, 0.001);
    Eigen::Vector3f lo = Eigen::Vector3f::Constant(1e9f), hi = -lo;
    for (const auto& v : r.mesh.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
    const Eigen::Vector3f truth = mesh.boundsMax() - mesh.boundsMin();
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(hi[k] - lo[k], truth[k], 0.005) << "axis " << k;
    EXPECT_GT(lo.z(), -0.0006);  // nothing under the table (the cleanup's tolerance)
    EXPECT_LT(lo.z(), foot_m);   // the foot on the table, or within the band of its noise
    EXPECT_LT(median(distancesToMesh(r.mesh.vertices, asMesh(mesh))), 0.0015);
  }
}

// Free poses on real scans: 4 Stanford bunny scans (decimated copies, tests/data/…/README.md), every
// pose but the first moved by 2° and 5 mm. Refined, they come back; kept, they do not.
TEST(Reconstruction, FreePosesOfRealScansComeBack) {
  const std::string conf = std::string(KEYTURN_TEST_DATA_DIR) + "/stanford-bunny-decimated/bun.conf";
  auto views = posedViews(conf, PoseReadOptions());
  ASSERT_EQ(views.size(), 4u);
  std::vector<Eigen::Matrix4d> truth;
  for (const auto& v : views) truth.push_back(v.world_from_view);
  const auto moved = perturbPoses(truth, 2, 0.005, 1);
  for (std::size_t i = 0; i < views.size(); ++i) views[i].world_from_view = moved[i];
  for (bool refine : {true, false}) {
    ReconstructionOptions o;
    o.registration.refine = refine;
    o.poisson.depth = 6;
    o.reference_poses = truth;
    const auto r = reconstruct(views, o);
    EXPECT_EQ(r.model, PoseModel::Free);
    double worst = 0, worst_t = 0;
    std::vector<double> moved_views;  // the rotation errors of the perturbed views
    for (std::size_t i = 0; i < r.outcomes.size(); ++i) {
      EXPECT_NEAR(r.outcomes[i].error_before->rotation_deg, i == 0 ? 0 : 2, 1e-6);
      worst = std::max(worst, r.outcomes[i].error_after->rotation_deg);
      worst_t = std::max(worst_t, r.outcomes[i].error_after->translation_m);
      if (i > 0) moved_views.push_back(r.outcomes[i].error_after->rotation_deg);
    }
    std::sort(moved_views.begin(), moved_views.end());
    if (refine) {
      // The target is on the median (0.25°). The worst view of these 4 decimated scans comes
      // back to 0.516° (the 10 full scans' worst: 0.607°, docs/reconstruction.md): 0.6 bounds it. (The
      // bar was 0.5 on an input GCC drew with the seed's axes in another order, which gave 0.371°.)
      EXPECT_LT(moved_views[moved_views.size() / 2], 0.25);
      EXPECT_LT(worst, 0.6);
      EXPECT_LT(worst_t, 0.001);
    } else {
      EXPECT_NEAR(worst, 2, 1e-6);
      EXPECT_NEAR(worst_t, 0.005, 1e-9);
    }
  }
}

TEST(Reconstruction, WritesWhatReadPosesReadsBack) {
  ReconstructionOptions o;
  o.registration.refine = false;
  o.poisson.depth = 6;
  const auto r = reconstruct(turn().views, o);
  const keyturn::test::ScratchFolder out("reconstruction_out");
  const std::string dir = out.path.string();
  writeReconstruction(dir, r, "test");
  for (const char* f : {"cloud.ply", "mesh.ply", "poses.txt", "report.json"}) EXPECT_GT(fs::file_size(dir + "/" + f), 100u) << f;
  const auto back = readPoses(dir + "/poses.txt");
  ASSERT_EQ(back.size(), r.views.size());
  for (std::size_t i = 0; i < back.size(); ++i) {
    EXPECT_EQ(back[i].file, r.views[i].file);
    EXPECT_LT((back[i].world_from_view - r.views[i].world_from_view).norm(), 1e-6);
  }
}

TEST(Reconstruction, ImpliedAxisOfATurn) {
  // A camera looking at a table whose axis (camera frame) is known: the poses imply it back.
  Eigen::Matrix4d camera_from_table = Eigen::Matrix4d::Identity();
  camera_from_table.topLeftCorner<3, 3>() = Eigen::AngleAxisd(2.0, Eigen::Vector3d(1, 0.2, 0).normalized()).toRotationMatrix();
  camera_from_table.topRightCorner<3, 1>() = Eigen::Vector3d(0.05, 0.1, 0.8);
  std::vector<Eigen::Matrix4d> poses;
  for (int k = 0; k < 6; ++k) poses.push_back((camera_from_table * rz(30.0 * k)).inverse());
  const auto a = impliedAxis(poses);
  const Eigen::Vector3d axis = camera_from_table.topLeftCorner<3, 3>() * Eigen::Vector3d::UnitZ();
  EXPECT_NEAR(std::abs(a.direction.dot(axis)), 1.0, 1e-9);
  const Eigen::Vector3d origin = camera_from_table.topRightCorner<3, 1>();
  EXPECT_LT((a.point - origin).cross(axis).norm(), 1e-9);  // on the axis
  EXPECT_NEAR(a.point.dot(a.direction), 0, 1e-9);          // the point nearest the camera
  EXPECT_THROW(impliedAxis({poses[0], poses[0]}), Error);
}

TEST(Reconstruction, PerturbationIsExactlyTheAmountAsked) {
  std::vector<Eigen::Matrix4d> poses(5, Eigen::Matrix4d::Identity());
  poses[2].topRightCorner<3, 1>() = Eigen::Vector3d(1, 2, 3);
  const auto p = perturbPoses(poses, 2, 0.005, 11);
  EXPECT_NEAR(poseDifference(poses[0], p[0]).rotation_deg, 0, 1e-12);
  for (int i = 1; i < 5; ++i) {
    EXPECT_NEAR(poseDifference(poses[i], p[i]).rotation_deg, 2, 1e-9);
    EXPECT_NEAR(poseDifference(poses[i], p[i]).translation_m, 0.005, 1e-12);
  }
  EXPECT_NE(p[1], perturbPoses(poses, 2, 0.005, 12)[1]);  // the seed matters
}

TEST(Reconstruction, TwoViewsThatDoNotOverlapAreRefused) {
  auto views = turn().views;
  views.resize(2);
  views[1].world_from_view(0, 3) += 1.0;  // a metre away: nothing in common
  views[1].turntable = views[0].turntable = false;
  ReconstructionOptions o;
  try {
    reconstruct(views, o);
    FAIL() << "no error";
  } catch (const NoOverlapError& e) {
    EXPECT_NE(std::string(e.what()).find("do not overlap"), std::string::npos) << e.what();
  }
}

// TSDF integration of the drill's 8 SR4000 frames on their true poses: the surface lies on the true
// mesh (its vertices 0.5 mm from it, median), and Auto chose it because every view is a depth
// frame. A view that is not one (the same points, unorganized) makes Auto fall back to Poisson with
// the reason, and an explicit TSDF stop with one line naming the file.
namespace {

std::vector<PosedView> truePosedTurn() {
  auto views = turn().views;
  for (std::size_t i = 0; i < views.size(); ++i) views[i].world_from_view = turn().truth[i];
  return views;
}

}  // namespace

TEST(Reconstruction, DepthFramesAreFusedByTsdfOntoTheTrueSurface) {
  ReconstructionOptions o;
  o.registration.refine = false;
  const auto r = reconstruct(truePosedTurn(), o);
  EXPECT_EQ(r.surface, SurfaceChoice::Tsdf);
  EXPECT_TRUE(r.surface_note.empty()) << r.surface_note;
  ASSERT_GT(r.mesh.triangles.size(), 1000u);
  // The views are in the drill's frame (truth), so the mesh is compared as it is.
  const auto d = distancesToMesh(r.mesh.vertices, asMesh(turn().mesh));
  EXPECT_LT(median(d), 0.0005);  // 0.41 mm measured
  const auto c = compareSurfaces(r.mesh, asMesh(turn().mesh), 0.001, 50000);
  EXPECT_GT(c.precision, 0.9);  // 0.94 measured: what the TSDF made lies on the drill
  EXPECT_GT(c.recall, 0.7);     // 0.78: 8 views at one elevation do not see the top or the foot
}

TEST(Reconstruction, AViewThatIsNotADepthFrameGetsPoissonOrOneLine) {
  const keyturn::test::ScratchFolder folder("reconstruction_not_a_frame");
  auto views = truePosedTurn();
  Cloud c = loadCloud(views[3].file);
  c.width = std::uint32_t(c.size()), c.height = 1;
  views[3].file = folder.made().string() + "/unorganized.pcd";
  saveCloud(views[3].file, c);
  ReconstructionOptions o;
  o.registration.refine = false;
  o.poisson.depth = 6;
  const auto r = reconstruct(views, o);
  EXPECT_EQ(r.surface, SurfaceChoice::Poisson);
  EXPECT_EQ(r.surface_note, "Poisson, not TSDF: " + views[3].file + ": not an organized depth frame (" +
                                std::to_string(c.size()) + " × 1)");
  o.surface = SurfaceChoice::Tsdf;
  try {
    reconstruct(views, o);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), views[3].file + ": not an organized depth frame (" + std::to_string(c.size()) +
                                         " × 1); a TSDF surface needs every view to be an organized depth frame (a "
                                         "Poisson surface does not)");
  }
}

// A flat object (the YCB plate, 26 cm wide, 2.7 cm tall) through the SR4000 at 30°: on some views the
// table's far side and the floor outnumber the plate, and describe's filter keeps the table ("not a
// support: the rest lies behind it"). Those views get their support cut with the plane the rig
// camera's other views found; without that, the table stays in the fused cloud.
TEST(Reconstruction, AFlatObjectsSupportIsCutWithItsRigCamerasPlane) {
  const sim::Mesh mesh = sim::loadMesh(std::string(KEYTURN_DATA_DIR) + "/objects/plate__ycb_029_plate.ply");
  sim::TofViewRenderer renderer(mesh);
  const keyturn::test::ScratchFolder folder("reconstruction_flat");
  std::vector<PosedView> views;
  for (int k = 0; k < 36; ++k) {
    sim::SceneView v;
    v.turntable_deg = 10.0 * k;
    v.seed = 300 + k;
    views.push_back(renderedView(renderer, mesh, v, folder.made().string() + "/a" + std::to_string(k) + ".pcd", "plate/ycb"));
  }
  // The fraction of fused points more than 20 mm off the plate: the table, which spreads past its
  // rim (the rim's own mixed pixels lie 10–13 mm off, 2 % of the points).
  auto farFromThePlate = [&](const Reconstruction& r) {
    const auto d = distancesToMesh(r.cloud.points, asMesh(mesh));
    return double(std::count_if(d.begin(), d.end(), [](double x) { return x > 0.02; })) / double(d.size());
  };
  ReconstructionOptions o;
  o.registration.refine = false;
  o.surface = SurfaceChoice::Poisson;
  o.poisson.depth = 6;
  const auto fixed = reconstruct(views, o);
  std::size_t cut = 0;
  for (const auto& v : fixed.outcomes) cut += v.support_from_rig_camera;
  EXPECT_GE(cut, 1u);
  EXPECT_LE(cut, 9u);  // most views found the table themselves (it is their camera's plane)
  EXPECT_LT(farFromThePlate(fixed), 0.002) << cut;  // 0 measured
  o.support_from_rig_camera = false;
  const auto kept = reconstruct(views, o);
  EXPECT_GT(farFromThePlate(kept), 0.3);  // 0.62 measured: the table those views kept
}
