// Google Benchmark suite for the descriptor chain on the built-in simulated
// SR4000 view of a mug (one thread). `keyturn bench` reports the same stages
// per view; this suite adds micro-benchmarks such as grid vs k-d tree search.
#include <benchmark/benchmark.h>

#include <pcl/filters/statistical_outlier_removal.h>
#include <pcl/point_types.h>
#include <pcl/search/kdtree.h>
#include <pcl/segmentation/extract_clusters.h>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <ctime>
#include <filesystem>
#include <memory>
#include <string>

#include "keyturn/core/cloud_io.h"
#include "keyturn/core/cloud_resample.h"
#include "keyturn/core/descriptor.h"
#include "keyturn/core/error.h"
#include "keyturn/core/filter.h"
#include "keyturn/core/geodesic.h"
#include "keyturn/core/histogram.h"
#include "keyturn/core/iss.h"
#include "keyturn/core/keypoint_functions.h"
#include "keyturn/core/keypoint_placement.h"
#include "keyturn/core/keypoint_refinement.h"
#include "keyturn/core/pcl_baselines.h"
#include "keyturn/core/radius_search.h"
#include "keyturn/core/worker_process.h"
#include "keyturn/learning/live_fusion.h"
#include "keyturn/learning/recognizer.h"
#include "keyturn/sim/mesh.h"
#include "keyturn/sim/structured_light_view.h"
#include "keyturn/sim/tof_view.h"

using namespace keyturn;

namespace {
struct Fixture {
  Cloud raw;
  Cloud filtered;
  PointSet set;
  std::unique_ptr<RadiusSearch> search;
  double res = 0;
  std::vector<int> keypoints;
  LocalCompleteGraph graph;
  Fixture() {
    raw = sim::builtinBenchmarkView();
    filtered = filterCloud(raw, FilterOptions());
    set = PointSet::fromCloud(filtered);
    search = std::make_unique<RadiusSearch>(set);
    res = cloudResolution(set, *search);
    keypoints = detectIssKeypoints(set, *search, res, IssOptions()).keypoints;
    graph = buildLocalCompleteGraph(set, *search, res, GraphOptions());
  }
};
const Fixture& fx() {
  static const Fixture f;
  return f;
}
}  // namespace

static void BM_Filter(benchmark::State& s) {
  for (auto _ : s) benchmark::DoNotOptimize(filterCloud(fx().raw, FilterOptions()));
}
BENCHMARK(BM_Filter)->Unit(benchmark::kMillisecond);

static void BM_FilterPlaneOnly(benchmark::State& s) {
  FilterOptions o;
  for (auto _ : s) {
    Cloud c = fx().raw;
    removeDominantPlane(c, o, nullptr);
    benchmark::DoNotOptimize(c);
  }
}
BENCHMARK(BM_FilterPlaneOnly)->Unit(benchmark::kMillisecond);

namespace {
pcl::PointCloud<pcl::PointXYZ>::Ptr toPcl(const Cloud& c) {
  pcl::PointCloud<pcl::PointXYZ>::Ptr out(new pcl::PointCloud<pcl::PointXYZ>);
  for (const auto& p : c.points)
    if (Cloud::isValid(p)) out->push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
  return out;
}
// A real Kinect crop (20,792 points): what the cluster step is given for a segmented cloud.
const Cloud& realCrop() {
  static const Cloud c = loadCloud(std::string(KEYTURN_REAL_DATA) + "/crop/learn0_o1.pcd");
  return c;
}
}  // namespace

// The outlier step as the chain runs it (after the working resolution, 2,054 points), against PCL's
// filter, which gives the same points (tests/core/outlier_removal_test.cpp).
static void BM_OutlierRemoval(benchmark::State& s) {
  const FilterOptions o;
  for (auto _ : s) {
    Cloud c = fx().filtered;
    removeStatisticalOutliers(c, o.sor_k, o.sor_std_mul);
    benchmark::DoNotOptimize(c);
  }
}
BENCHMARK(BM_OutlierRemoval)->Unit(benchmark::kMillisecond);

static void BM_PclOutlierRemoval(benchmark::State& s) {
  const FilterOptions o;
  const auto pts = toPcl(fx().filtered);
  for (auto _ : s) {
    pcl::StatisticalOutlierRemoval<pcl::PointXYZ> sor;
    sor.setInputCloud(pts);
    sor.setMeanK(o.sor_k);
    sor.setStddevMulThresh(o.sor_std_mul);
    pcl::Indices kept;
    sor.filter(kept);
    benchmark::DoNotOptimize(kept);
  }
}
BENCHMARK(BM_PclOutlierRemoval)->Unit(benchmark::kMillisecond);

// The largest connected component at 15 mm on the real crop, against PCL's Euclidean clustering.
static void BM_LargestCluster(benchmark::State& s) {
  const FilterOptions o;
  for (auto _ : s) {
    Cloud c = realCrop();
    keepLargestCluster(c, o.cluster_tolerance);
    benchmark::DoNotOptimize(c);
  }
}
BENCHMARK(BM_LargestCluster)->Unit(benchmark::kMillisecond);

static void BM_PclEuclideanClusters(benchmark::State& s) {
  const FilterOptions o;
  const auto pts = toPcl(realCrop());
  for (auto _ : s) {
    pcl::search::KdTree<pcl::PointXYZ>::Ptr tree(new pcl::search::KdTree<pcl::PointXYZ>);
    pcl::EuclideanClusterExtraction<pcl::PointXYZ> ec;
    ec.setClusterTolerance(o.cluster_tolerance);
    ec.setSearchMethod(tree);
    ec.setInputCloud(pts);
    std::vector<pcl::PointIndices> clusters;
    ec.extract(clusters);
    benchmark::DoNotOptimize(clusters);
  }
}
BENCHMARK(BM_PclEuclideanClusters)->Unit(benchmark::kMillisecond);

static void BM_RadiusGrid(benchmark::State& s) {
  std::vector<int> nb;
  const float r = static_cast<float>(6 * fx().res);
  for (auto _ : s)
    for (std::size_t i = 0; i < fx().set.size(); ++i) fx().search->radius(static_cast<int>(i), r, nb);
  s.SetItemsProcessed(s.iterations() * fx().set.size());
}
BENCHMARK(BM_RadiusGrid)->Unit(benchmark::kMillisecond);

static void BM_RadiusKdTree(benchmark::State& s) {
  const auto tree = RadiusSearch::kdTree(fx().set);
  std::vector<int> nb;
  const float r = static_cast<float>(6 * fx().res);
  for (auto _ : s)
    for (std::size_t i = 0; i < fx().set.size(); ++i) tree->radius(static_cast<int>(i), r, nb);
  s.SetItemsProcessed(s.iterations() * fx().set.size());
}
BENCHMARK(BM_RadiusKdTree)->Unit(benchmark::kMillisecond);

static void BM_Iss(benchmark::State& s) {
  for (auto _ : s) benchmark::DoNotOptimize(detectIssKeypoints(fx().set, *fx().search, fx().res, IssOptions()));
  s.counters["K"] = static_cast<double>(fx().keypoints.size());
}
BENCHMARK(BM_Iss)->Unit(benchmark::kMillisecond);

static void BM_PclIss(benchmark::State& s) {
  const IssOptions o;
  for (auto _ : s)
    benchmark::DoNotOptimize(pclIssKeypoints(fx().set, o.frame_radius * fx().res, o.nms_radius * fx().res,
                                             o.gamma21, o.gamma32, o.min_neighbors));
}
BENCHMARK(BM_PclIss)->Unit(benchmark::kMillisecond);

// OUR-CVFH runs in the worker program (worker_process.h): the whole call, and the worker's round
// trip alone (the view's points there and back) against what the fork of each call it replaced cost
// in this same process (fork, the points back through a pipe, waitpid).
static void BM_PclOurCvfh(benchmark::State& s) {
  for (auto _ : s) benchmark::DoNotOptimize(pclOurCvfh(fx().set, 0.012));
}
BENCHMARK(BM_PclOurCvfh)->Unit(benchmark::kMillisecond);

static std::vector<float> setAsFloats() {
  std::vector<float> v;
  for (const auto& p : fx().set.points) v.insert(v.end(), {p.x(), p.y(), p.z()});
  return v;
}

static void BM_WorkerRoundTrip(benchmark::State& s) {
  const std::vector<float> in = setAsFloats();
  for (auto _ : s) benchmark::DoNotOptimize(inWorkerProcess({"echo", in}, "bench", "crashed", "here"));
  s.counters["floats"] = static_cast<double>(in.size());
}
BENCHMARK(BM_WorkerRoundTrip)->Unit(benchmark::kMillisecond);

static void BM_ForkRoundTrip(benchmark::State& s) {
  const std::vector<float> in = setAsFloats();
  for (auto _ : s) {
    int fds[2];
    if (::pipe(fds) != 0) return s.SkipWithError("pipe");
    const pid_t child = ::fork();
    if (child == 0) {
      const auto bytes = static_cast<ssize_t>(in.size() * sizeof(float));
      ::_exit(::write(fds[1], in.data(), static_cast<std::size_t>(bytes)) == bytes ? 0 : 1);
    }
    ::close(fds[1]);
    std::vector<float> out(in.size());
    std::size_t got = 0;
    for (ssize_t n; got < out.size() * sizeof(float) &&
                    (n = ::read(fds[0], reinterpret_cast<char*>(out.data()) + got, out.size() * sizeof(float) - got)) > 0;)
      got += static_cast<std::size_t>(n);
    ::close(fds[0]);
    int status = 0;
    ::waitpid(child, &status, 0);
    benchmark::DoNotOptimize(out);
  }
}
BENCHMARK(BM_ForkRoundTrip)->Unit(benchmark::kMillisecond);

static void BM_Kpd(benchmark::State& s) {
  std::vector<Eigen::Vector3f> kp;
  for (int i : fx().keypoints) kp.push_back(fx().set.points[i]);
  for (auto _ : s) {
    benchmark::DoNotOptimize(keypointDistances(kp));
    benchmark::DoNotOptimize(keypointSqrtAreas(kp));
    benchmark::DoNotOptimize(keypointAngles(kp));
  }
}
BENCHMARK(BM_Kpd)->Unit(benchmark::kMicrosecond);

// KPA3's 32-bin PDF: the histogram of every angle (0) against the binning that needs an arccos
// only near a bin edge (1), the chain's; the same numbers (tested).
static void BM_KpaPdf(benchmark::State& s) {
  std::vector<Eigen::Vector3f> kp;
  for (int i : fx().keypoints) kp.push_back(fx().set.points[i]);
  const HistogramRange range{0.0, M_PI};
  // 0: every angle, then its histogram; 1: binned as computed, hard bins; 2: linear bins (the default)
  for (auto _ : s)
    benchmark::DoNotOptimize(s.range(0) == 2   ? keypointAnglePdf(kp, 32, range, Binning::Linear)
                             : s.range(0) == 1 ? keypointAnglePdf(kp, 32, range)
                                               : histogramPdf(keypointAngles(kp), 32, range));
}
BENCHMARK(BM_KpaPdf)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond);

static void BM_GraphBuild(benchmark::State& s) {
  for (auto _ : s)
    benchmark::DoNotOptimize(buildLocalCompleteGraph(fx().set, *fx().search, fx().res, GraphOptions()));
  s.counters["edges"] = static_cast<double>(fx().graph.edgeCount());
  s.counters["curved_edges"] = static_cast<double>(fx().graph.curvedEdgeCount());
}
BENCHMARK(BM_GraphBuild)->Unit(benchmark::kMillisecond);

// The geodesic searches on the fixture's keypoints, with the scalar relaxation loop forced or not.
static void timeGeodesics(benchmark::State& s, bool scalar) {
  const int which = static_cast<int>(s.range(0));
  detail::useScalarGeodesics(scalar);
  for (auto _ : s)
    benchmark::DoNotOptimize(geodesicKeypointDistances(fx().graph, fx().set, fx().keypoints, which));
  detail::useScalarGeodesics(false);
}

static void BM_Geodesics(benchmark::State& s) { timeGeodesics(s, false); }
BENCHMARK(BM_Geodesics)->Arg(kGkpd1)->Arg(kGkpd2)->Arg(kGkpcd2)->Unit(benchmark::kMillisecond);

static void BM_DescribeView(benchmark::State& s) {
  const DescriptorOptions o;
  for (auto _ : s) benchmark::DoNotOptimize(describeView(fx().raw, o));
}
BENCHMARK(BM_DescribeView)->Unit(benchmark::kMillisecond);

// Keypoint placement on the 38 real mOSD crops (issue 49's cost target: ≤ 2 ms a real view, median,
// one thread): each view prepared and its chain keypoints found once; each run places them.
// Arg: 0 nearest, 1 salient, 2 the refinement (--refine-keypoints 0.5). median_ms: the median over
// views of each view's thread CPU time.
struct PreparedCrop {
  PreparedView view;
  std::vector<Eigen::Vector3f> keypoints;
  double resolution = 0;
};
static const std::vector<PreparedCrop>& realCrops() {
  static const std::vector<PreparedCrop> crops = [] {
    std::vector<std::string> files;
    for (const auto& e : std::filesystem::directory_iterator(std::string(KEYTURN_REAL_DATA) + "/crop"))
      if (e.path().extension() == ".pcd") files.push_back(e.path().string());
    std::sort(files.begin(), files.end());
    std::vector<PreparedCrop> out;
    DescriptorOptions o;
    o.placement.placement = KeypointPlacement::Salient;  // keeps the measured view
    o.features = {Feature::KPD2};
    for (const auto& f : files) {
      PreparedCrop c;
      c.view = prepareView(loadCloud(f), o);
      const ViewDescriptor d = describeFilteredPoints(c.view.points, o, c.view.resolutionFloor());
      for (int i : d.keypoint_index) c.keypoints.push_back(c.view.points.points[i]);
      c.resolution = d.resolution;
      if (c.view.measured.size() >= 2) out.push_back(std::move(c));
    }
    return out;
  }();
  return crops;
}
static double threadCpuMs() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return t.tv_sec * 1e3 + t.tv_nsec * 1e-6;
}
static void BM_KeypointPlacement(benchmark::State& s) {
  const auto& crops = realCrops();
  const IssOptions iss;
  KeypointPlacementOptions p;
  p.placement = s.range(0) == 0 ? KeypointPlacement::Nearest : KeypointPlacement::Salient;
  KeypointRefinementOptions r;
  r.enabled = true;
  std::vector<double> each;
  for (auto _ : s)
    for (const auto& c : crops) {
      const double t0 = threadCpuMs();
      benchmark::DoNotOptimize(s.range(0) == 2
                                   ? refineKeypointsOnMeasuredPoints(c.view.measured, c.keypoints, c.resolution, iss, r)
                                   : placeKeypoints(c.view.measured, c.keypoints, c.resolution, iss, p));
      each.push_back(threadCpuMs() - t0);
    }
  std::nth_element(each.begin(), each.begin() + static_cast<long>(each.size() / 2), each.end());
  s.counters["median_ms"] = each.empty() ? 0.0 : each[each.size() / 2];
  s.counters["views"] = static_cast<double>(crops.size());
}
BENCHMARK(BM_KeypointPlacement)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

// One simulated SR4000 frame (176 × 144, rays through the 177 × 145 pixel corners) of a
// 10k-triangle YCB mesh on the turntable.
static void BM_RenderView(benchmark::State& s) {
  sim::TofViewRenderer r(sim::loadMesh(KEYTURN_DATA_DIR "/objects/drill__ycb_035_power_drill.ply"));
  sim::SceneView v;
  r.render(v);  // BVH built once per turntable angle
  for (auto _ : s) {
    v.seed++;
    benchmark::DoNotOptimize(r.render(v));
  }
}
BENCHMARK(BM_RenderView)->Unit(benchmark::kMillisecond);

// One simulated Kinect-class frame (640 × 480 depth, colour and IR: a ray and a projector shadow
// ray per pixel) while the turntable turns, so every frame is cast anew: the simulated OpenNI2
// camera's cost per frame in the studio with the table moving (issue 52: it must keep 30 frames/s).
static void BM_RenderStructuredLightTurning(benchmark::State& s) {
  sim::StructuredLightRenderer r(sim::loadMesh(KEYTURN_DATA_DIR "/objects/mug__ycb_025_mug.ply"));
  sim::SceneView v;
  for (auto _ : s) {
    v.turntable_deg += 0.7;  // 20°/s at 30 frames/s
    v.seed++;
    benchmark::DoNotOptimize(r.render(v));
  }
}
BENCHMARK(BM_RenderStructuredLightTurning)->Unit(benchmark::kMillisecond);

// The same camera with the table still: only the noise is drawn anew.
static void BM_RenderStructuredLightStill(benchmark::State& s) {
  sim::StructuredLightRenderer r(sim::loadMesh(KEYTURN_DATA_DIR "/objects/mug__ycb_025_mug.ply"));
  sim::SceneView v;
  for (auto _ : s) {
    v.seed++;
    benchmark::DoNotOptimize(r.render(v));
  }
}
BENCHMARK(BM_RenderStructuredLightStill)->Unit(benchmark::kMillisecond);

// The simulated OpenNI2 device's open (issue 51): a fresh scene built (Embree BVH) and cast for the
// view (the table's pixels, each pixel's noise model), which until then its first frame did.
static void BM_OpenStructuredLightScene(benchmark::State& s) {
  const sim::Mesh mug = sim::loadMesh(KEYTURN_DATA_DIR "/objects/mug__ycb_025_mug.ply");
  sim::SceneView v;
  for (auto _ : s) {
    sim::StructuredLightRenderer r(mug);
    r.prepare(v);
    benchmark::DoNotOptimize(r.casts());
  }
}
BENCHMARK(BM_OpenStructuredLightScene)->Unit(benchmark::kMillisecond);

// The first frame of a device whose scene its open prepared: noise only, as a still frame.
static void BM_FirstFrameOfAPreparedScene(benchmark::State& s) {
  const sim::Mesh mug = sim::loadMesh(KEYTURN_DATA_DIR "/objects/mug__ycb_025_mug.ply");
  sim::SceneView v;
  for (auto _ : s) {
    s.PauseTiming();
    auto r = std::make_unique<sim::StructuredLightRenderer>(mug);
    r->prepare(v);
    s.ResumeTiming();
    benchmark::DoNotOptimize(r->render(v));
    s.PauseTiming();
    r.reset();
    s.ResumeTiming();
  }
}
BENCHMARK(BM_FirstFrameOfAPreparedScene)->Unit(benchmark::kMillisecond);

// The same first frame with nothing prepared, as the device gave it before: the whole cast in it.
static void BM_FirstFrameOfAnUnpreparedScene(benchmark::State& s) {
  const sim::Mesh mug = sim::loadMesh(KEYTURN_DATA_DIR "/objects/mug__ycb_025_mug.ply");
  sim::SceneView v;
  for (auto _ : s) {
    s.PauseTiming();
    auto r = std::make_unique<sim::StructuredLightRenderer>(mug);
    s.ResumeTiming();
    benchmark::DoNotOptimize(r->render(v));
    s.PauseTiming();
    r.reset();
    s.ResumeTiming();
  }
}
BENCHMARK(BM_FirstFrameOfAnUnpreparedScene)->Unit(benchmark::kMillisecond);

// Live recognition as the studio runs it: the built-in model (KPD2 + KPA3, XGBoost)
// on one simulated SR4000 frame of the drill — filter, describe, classify.
static void BM_RecognizeLive(benchmark::State& s) {
  const auto recognizer = learning::Recognizer::load(KEYTURN_DATA_DIR "/models/sim-objects");
  sim::TofViewRenderer r(sim::loadMesh(KEYTURN_DATA_DIR "/objects/drill__ycb_035_power_drill.ply"));
  sim::SceneView v;
  v.turntable_deg = 40;
  const Cloud frame = r.render(v);
  for (auto _ : s) benchmark::DoNotOptimize(recognizer.recognize(frame));
}
BENCHMARK(BM_RecognizeLive)->Unit(benchmark::kMillisecond);

// The studio's fused belief at rest after a turn of N views (72: a whole turn; the built-in model's
// pose references): each frame replaces the newest bin's view (its pose evidence, then the state).
static void BM_LiveFusionFrameAtRest(benchmark::State& s) {
  const auto recognizer = learning::Recognizer::load(KEYTURN_DATA_DIR "/models/sim-objects");
  const auto& info = recognizer.info();
  learning::LiveFusion fusion(info);
  const std::vector<float> p(info.classes.size(), 1.f / static_cast<float>(info.classes.size()));
  std::vector<float> features(info.pose_references.mean.size());
  for (std::size_t k = 0; k < features.size(); ++k) features[k] = info.pose_references.mean[k] + 0.01f * static_cast<float>(k % 7);
  const auto views = static_cast<std::size_t>(s.range(0));
  for (std::size_t b = 0; b < views; ++b) fusion.add(learning::Answer::Class, 1.0, p, features, 5.0 * static_cast<double>(b));
  if (fusion.views() != views) s.SkipWithError("the turn did not take its views");
  const double newest = 5.0 * static_cast<double>(views - 1) + 0.5;
  for (auto _ : s) benchmark::DoNotOptimize(fusion.add(learning::Answer::Class, 1.0, p, features, newest));
}
BENCHMARK(BM_LiveFusionFrameAtRest)->Arg(1)->Arg(72)->Unit(benchmark::kMicrosecond);

// The real 640 × 480 Kinect frame at the sizes of `keyturn bench --scaling` and by the
// same rule (docs/benchmarks.md, "Scaling"): the object the filter cuts from the full
// frame, as seeded random subsets, up to its size; the frame resampled to N pixels above.
namespace {
struct RealFrame {
  Cloud frame = loadCloud(KEYTURN_DATA_DIR "/frames/mosd_learn0.pcd");
  Cloud object = filterCloud(frame, FilterOptions());
  Cloud input(std::size_t n) const {
    return n <= object.validCount() ? randomSubset(object, n, 7) : resampleOrganized(frame, n);
  }
};
const RealFrame& realFrame() {
  static const RealFrame f;
  return f;
}
}  // namespace

static void BM_DescribeRealScaling(benchmark::State& s) {
  const Cloud in = realFrame().input(static_cast<std::size_t>(s.range(0)));
  const DescriptorOptions o;
  ViewDescriptor d;
  try {
    d = describeView(in, o);
  } catch (const Error& e) {
    s.SkipWithError(e.what());
    return;
  }
  for (auto _ : s) benchmark::DoNotOptimize(describeView(in, o));
  s.counters["K"] = d.keypointCount();
  s.counters["points"] = static_cast<double>(d.points);
}
BENCHMARK(BM_DescribeRealScaling)->Arg(1000)->Arg(3000)->Arg(10000)->Arg(30000)->Arg(100000)->Arg(307200)
    ->Unit(benchmark::kMillisecond);

// PCL's ESF on the points the chain keeps from the same inputs.
static void BM_PclEsfRealScaling(benchmark::State& s) {
  const PointSet set =
      PointSet::fromCloud(filterCloud(realFrame().input(static_cast<std::size_t>(s.range(0))), FilterOptions()));
  if (set.size() == 0) {
    s.SkipWithError("the filter leaves no points");
    return;
  }
  for (auto _ : s) benchmark::DoNotOptimize(pclEsf(set));
  s.counters["points"] = static_cast<double>(set.size());
}
BENCHMARK(BM_PclEsfRealScaling)->Arg(1000)->Arg(3000)->Arg(10000)->Arg(30000)->Arg(100000)->Arg(307200)
    ->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();

// The geodesic searches with the scalar relaxation loop forced: the AVX2 path's gain.
static void BM_GeodesicsScalar(benchmark::State& s) { timeGeodesics(s, true); }
BENCHMARK(BM_GeodesicsScalar)->Arg(kGkpd2)->Arg(kGkpcd2)->Unit(benchmark::kMillisecond);
