// The peers keyturn compares against: ESF made repeatable, VFH and OUR-CVFH
// returning their histograms (OUR-CVFH from the worker program).
#include "keyturn/core/pcl_baselines.h"

#include <gtest/gtest.h>

#include <chrono>
#include <numeric>
#include <thread>

#include "keyturn/core/error.h"
#include "support/synthetic_clouds.h"
#include "support/under_asan.h"

using namespace keyturn;

namespace {

PointSet cylinder() {
  return PointSet::fromCloud(test::unorganized(test::cylinderSurface(0.04f, 0.1f, 60, 30)));
}

}  // namespace

TEST(PclBaselines, SeededEsfRepeatsAcrossSecondsAndChangesWithTheSeed) {
  // PCL's own ESF reseeds from time(): two calls a second apart differ. Seeded ones must not.
  const PointSet set = cylinder();
  const auto a = pclEsfSeeded(set, 7);
  std::this_thread::sleep_for(std::chrono::milliseconds(1100));
  const auto b = pclEsfSeeded(set, 7);
  const auto c = pclEsfSeeded(set, 8);
  ASSERT_EQ(a.size(), 640u);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
  EXPECT_GT(std::accumulate(a.begin(), a.end(), 0.0), 0.0);
}

TEST(PclBaselines, VfhAndOurCvfhGiveTheirHistograms) {
#ifdef KEYTURN_UNDER_ASAN
  // ASan stops PCL's OUR-CVFH on every cloud: it frees Eigen's aligned-malloc
  // memory with operator delete (alloc-dealloc-mismatch inside libpcl_features).
  // The worker turns that into an error (next test); the histogram is checked in
  // the normal build. A plain skip, also on CI: no build of PCL that CI can install passes ASan here.
  GTEST_SKIP() << "PCL's OUR-CVFH trips ASan's alloc-dealloc-mismatch check inside libpcl_features";
#endif
  // A box: its faces are the smooth regions OUR-CVFH builds frames on. (On some
  // clouds, the cylinder among them in the clang build, PCL 1.13's OUR-CVFH
  // aborts: that must come back as keyturn::Error, never take the process down.)
  const PointSet set = PointSet::fromCloud(test::unorganized(test::cubeSurface(0.1f, 25, Eigen::Vector3f(0, 0, 0.6f))));
  const auto vfh = pclVfh(set, 0.012);
  const auto cvfh = pclOurCvfh(set, 0.012);
  ASSERT_EQ(vfh.size(), 308u);
  ASSERT_EQ(cvfh.size(), 308u);
  EXPECT_GT(std::accumulate(cvfh.begin(), cvfh.end(), 0.0), 0.0);
  // Same input, same answer from the worker (a kept one: worker_process.h).
  EXPECT_EQ(pclOurCvfh(set, 0.012), cvfh);
}

// Which of the two PCL does on these cylinders depends on the build (the clang build aborts in
// OUR-CVFH): a survival check. The crash path itself is tested in WorkerProcess.ACrashIsAnErrorNamingTheSignalAndTheNextCallGetsANewWorker.
TEST(PclBaselines, OurCvfhOnCylindersIsAFilledHistogramOrAnErrorNamingOurCvfh) {
  for (const PointSet& set : {cylinder(), PointSet::fromCloud(test::unorganized(test::cylinderSurface(0.02f, 0.3f, 20, 60)))}) {
    try {
      const auto h = pclOurCvfh(set, 0.012);
      ASSERT_EQ(h.size(), 308u);
      EXPECT_GT(std::accumulate(h.begin(), h.end(), 0.0), 0.0);
    } catch (const Error& e) {
      EXPECT_EQ(std::string(e.what()).rfind("PCL's OUR-CVFH crashed on this view (signal ", 0), 0u) << e.what();
    }
  }
}
