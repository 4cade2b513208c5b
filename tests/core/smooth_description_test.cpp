// The levers that make a view's description move continuously with its input (issue 30):
// linear binning, kernel smoothing, weighted values and ISS's weighted budget.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>

#include "keyturn/core/descriptor.h"
#include "keyturn/core/dissimilarity.h"
#include "keyturn/core/histogram.h"
#include "keyturn/core/iss.h"
#include "keyturn/core/keypoint_functions.h"
#include "keyturn/core/radius_search.h"
#include "keyturn/sim/tof_view.h"

namespace keyturn {
namespace {

TEST(LinearBinning, SharesAValueBetweenTheTwoNearestBinCentres) {
  const HistogramRange r{0.0, 1.0};  // 4 bins, centres 0.125, 0.375, 0.625, 0.875
  EXPECT_EQ(histogramPdf({0.375f}, 4, r, nullptr, Binning::Linear), (std::vector<double>{0, 1, 0, 0}));
  const auto half = histogramPdf({0.5f}, 4, r, nullptr, Binning::Linear);
  EXPECT_NEAR(half[1], 0.5, 1e-6);
  EXPECT_NEAR(half[2], 0.5, 1e-6);
  const auto quarter = histogramPdf({0.4375f}, 4, r, nullptr, Binning::Linear);
  EXPECT_NEAR(quarter[1], 0.75, 1e-6);
  EXPECT_NEAR(quarter[2], 0.25, 1e-6);
  // Below the first centre and past the range: all in the end bins; NaN ignored.
  EXPECT_EQ(histogramPdf({0.05f, -3.f, NAN}, 4, r, nullptr, Binning::Linear), (std::vector<double>{1, 0, 0, 0}));
  EXPECT_EQ(histogramPdf({0.9f, 7.f}, 4, r, nullptr, Binning::Linear), (std::vector<double>{0, 0, 0, 1}));
}

// A value moved by δ moves at most 2δ/width of its mass with linear binning; with hard binning
// crossing an edge moves all of it.
TEST(LinearBinning, MovesContinuouslyWithTheValues) {
  const HistogramRange r{0.0, 1.0};
  std::vector<float> v(200), moved(200);
  for (int i = 0; i < 200; ++i) v[i] = 0.1f + 0.004f * static_cast<float>(i), moved[i] = v[i] + 0.001f;
  const double linear = l1Distance(histogramPdf(v, 16, r, nullptr, Binning::Linear),
                                   histogramPdf(moved, 16, r, nullptr, Binning::Linear));
  EXPECT_LE(linear, 2 * 0.001 * 16 + 1e-9);
  const double hard = l1Distance(histogramPdf(v, 16, r), histogramPdf(moved, 16, r));
  EXPECT_GT(hard, 2 * linear);
}

// The quadratic B-spline over the three nearest bins: 1/8, 3/4, 1/8 at a centre, halves at an edge,
// the mass kept at the ends; its weights change with a continuous slope, so a few values moving a
// little move less mass than with linear binning.
TEST(QuadraticBinning, SpreadsAValueOverThreeBinsAndKeepsItsMass) {
  const HistogramRange r{0.0, 1.0};  // 4 bins, centres 0.125, 0.375, 0.625, 0.875
  const auto centre = histogramPdf({0.375f}, 4, r, nullptr, Binning::Quadratic);
  EXPECT_NEAR(centre[0], 0.125, 1e-6);
  EXPECT_NEAR(centre[1], 0.75, 1e-6);
  EXPECT_NEAR(centre[2], 0.125, 1e-6);
  EXPECT_NEAR(centre[3], 0.0, 1e-12);
  const auto edge = histogramPdf({0.5f}, 4, r, nullptr, Binning::Quadratic);
  EXPECT_NEAR(edge[1], 0.5, 1e-6);
  EXPECT_NEAR(edge[2], 0.5, 1e-6);
  // At the ends nothing leaves the range: the first bin's centre keeps 7/8, below it all of it.
  const auto first = histogramPdf({0.125f}, 4, r, nullptr, Binning::Quadratic);
  EXPECT_NEAR(first[0], 0.875, 1e-6);
  EXPECT_EQ(histogramPdf({-3.f, NAN}, 4, r, nullptr, Binning::Quadratic), (std::vector<double>{1, 0, 0, 0}));
  EXPECT_EQ(histogramPdf({7.f}, 4, r, nullptr, Binning::Quadratic), (std::vector<double>{0, 0, 0, 1}));
  for (float v : {0.01f, 0.2f, 0.49f, 0.77f, 0.99f}) {
    const auto pdf = histogramPdf({v}, 4, r, nullptr, Binning::Quadratic);
    EXPECT_NEAR(std::accumulate(pdf.begin(), pdf.end(), 0.0), 1.0, 1e-12) << v;
  }
  // Eight values moved by a tenth of a bin: less mass moves than with linear binning.
  std::vector<float> few, moved;
  for (int i = 0; i < 8; ++i) few.push_back(0.06f + 0.11f * static_cast<float>(i)), moved.push_back(few.back() + 0.00625f);
  const auto l1 = [&](Binning b) {
    return l1Distance(histogramPdf(few, 16, r, nullptr, b), histogramPdf(moved, 16, r, nullptr, b));
  };
  EXPECT_LT(l1(Binning::Quadratic), 0.8 * l1(Binning::Linear));
}

// A kernel density PDF: one bin's mass spread as a Gaussian of σ bins (1 : e^-1/2 : e^-2 at σ 1),
// reflected back at the outer edges so nothing leaves the range; σ 0 leaves the PDF as it was.
TEST(PdfSmoothing, SpreadsEachBinAsAGaussianAndKeepsTheMass) {
  std::vector<double> delta(9, 0.0);
  delta[4] = 1.0;
  std::vector<double> same = delta;
  smoothPdf(same, 0.0);
  EXPECT_EQ(same, delta);
  std::vector<double> g = delta;
  smoothPdf(g, 1.0);
  EXPECT_NEAR(g[3] / g[4], std::exp(-0.5), 1e-12);
  EXPECT_NEAR(g[6] / g[4], std::exp(-2.0), 1e-12);
  EXPECT_NEAR(g[3], g[5], 1e-15);
  EXPECT_EQ(g[0], 0.0);  // beyond 3 σ
  EXPECT_NEAR(std::accumulate(g.begin(), g.end(), 0.0), 1.0, 1e-12);
  // At an end, what would fall past the edge is reflected back: bin 0 gets its own and its mirror's share.
  std::vector<double> end(9, 0.0);
  end[0] = 1.0;
  smoothPdf(end, 1.0);
  EXPECT_NEAR(std::accumulate(end.begin(), end.end(), 0.0), 1.0, 1e-12);
  EXPECT_NEAR(end[1] / end[0], (std::exp(-0.5) + std::exp(-2.0)) / (1.0 + std::exp(-0.5)), 1e-12);
  EXPECT_GT(end[0], end[1]);
}

// The lever it is for: a few values swapped for others a bin or two away move less mass once the
// PDFs are smoothed, while two clearly different sets stay far apart.
TEST(PdfSmoothing, ValuesMovedByABinMoveLessMassThanTwoDifferentSets) {
  const HistogramRange r{0.0, 1.0};
  std::vector<float> v, moved, other;
  for (int i = 0; i < 64; ++i) {
    v.push_back(0.2f + 0.3f * static_cast<float>(i % 8) / 8.f);
    moved.push_back(v.back() + (i % 4 == 0 ? 0.05f : 0.f));  // a quarter moved by 1.6 bins of 32
    other.push_back(0.5f + 0.4f * static_cast<float>(i % 8) / 8.f);
  }
  const auto dist = [&](const std::vector<float>& a, const std::vector<float>& b, double sigma) {
    auto pa = histogramPdf(a, 32, r, nullptr, Binning::Linear), pb = histogramPdf(b, 32, r, nullptr, Binning::Linear);
    smoothPdf(pa, sigma);
    smoothPdf(pb, sigma);
    return l1Distance(pa, pb);
  };
  EXPECT_LT(dist(v, moved, 1.5), 0.6 * dist(v, moved, 0.0));
  EXPECT_GT(dist(v, other, 1.5), 0.8 * dist(v, other, 0.0));
}

TEST(WeightedHistogram, AWeightCountsAsRepeatedValues) {
  const HistogramRange r{0.0, 1.0};
  const std::vector<float> w = {2.f, 1.f, 0.5f};
  const auto weighted = histogramPdf({0.1f, 0.6f, 0.9f}, 4, r, nullptr, Binning::Hard, &w);
  const auto repeated = histogramPdf({0.1f, 0.1f, 0.1f, 0.1f, 0.6f, 0.6f, 0.9f}, 4, r);
  for (int b = 0; b < 4; ++b) EXPECT_NEAR(weighted[b], repeated[b], 1e-12) << b;
}

std::vector<Eigen::Vector3f> somePoints(int n) {
  std::vector<Eigen::Vector3f> p;
  for (int i = 0; i < n; ++i)
    p.emplace_back(std::sin(1.3f * i) * 0.1f, std::cos(0.7f * i) * 0.08f, 0.5f + 0.05f * std::sin(2.1f * i));
  return p;
}

TEST(WeightedKeypointFunctions, PairAndTripleWeightsFollowTheValueOrder) {
  const std::vector<double> w = {1.0, 0.5, 0.25, 2.0};
  EXPECT_EQ(pairWeights(w), (std::vector<float>{0.5f, 0.25f, 2.f, 0.125f, 1.f, 0.5f}));
  EXPECT_EQ(tripleWeights(w), (std::vector<float>{0.125f, 1.f, 0.5f, 0.25f}));
  const auto kp = somePoints(12);
  EXPECT_EQ(pairWeights(std::vector<double>(12, 1.0)).size(), keypointDistances(kp).size());
  EXPECT_EQ(tripleWeights(std::vector<double>(12, 1.0)).size(), keypointSqrtAreas(kp).size());
}

TEST(WeightedKeypointFunctions, AnglePdfOfUnitWeightsIsTheLinearHistogramOfTheAngles) {
  const auto kp = somePoints(20);
  const HistogramRange r{0.0, M_PI};
  const std::vector<double> ones(kp.size(), 1.0);
  const auto weighted = keypointAnglePdf(kp, 32, r, Binning::Linear, &ones);
  const auto exact = histogramPdf(keypointAngles(kp), 32, r, nullptr, Binning::Linear);
  EXPECT_LT(l1Distance(weighted, exact), 2e-3);  // the polynomial arccos: ≤ 6.7e-5 rad per angle
  // A keypoint of weight 0 is as if it were not there.
  std::vector<double> w = ones;
  w[5] = 0.0;
  std::vector<Eigen::Vector3f> without = kp;
  without.erase(without.begin() + 5);
  EXPECT_LT(l1Distance(keypointAnglePdf(kp, 32, r, Binning::Linear, &w),
                       keypointAnglePdf(without, 32, r, Binning::Linear)), 1e-9);
}

TEST(WeightedBudget, WeighsTheLeastSalientKeypointsLessDownToTheFirstLeftOut) {
  const Cloud view = sim::builtinBenchmarkView();
  DescriptorOptions o;
  const PreparedView prepared = prepareView(view, o);
  const RadiusSearch search(prepared.points);
  const double res = std::max(cloudResolution(prepared.points, search), prepared.resolutionFloor());
  IssOptions iss = o.iss;
  iss.max_keypoints = 0;
  const IssResult all = detectIssKeypoints(prepared.points, search, res, iss);
  ASSERT_GT(all.keypoints.size(), 40u);
  iss.max_keypoints = 32;
  EXPECT_TRUE(detectIssKeypoints(prepared.points, search, res, iss).weight.empty()) << "a hard budget weighs nothing";
  iss.budget_taper = 0.5;
  const IssResult soft = detectIssKeypoints(prepared.points, search, res, iss);
  ASSERT_EQ(soft.keypoints.size(), 32u);
  ASSERT_EQ(soft.weight.size(), 32u);
  std::vector<double> s;
  for (int i : all.keypoints) s.push_back(all.saliency[i]);
  std::sort(s.begin(), s.end(), std::greater<double>());
  const double top = s[15], edge = s[32];
  int full = 0;
  for (std::size_t k = 0; k < soft.keypoints.size(); ++k) {
    const double sal = soft.saliency[soft.keypoints[k]];
    EXPECT_NEAR(soft.weight[k], std::clamp((sal - edge) / (top - edge), 0.0, 1.0), 1e-12);
    full += soft.weight[k] == 1.0;
  }
  EXPECT_EQ(full, 16);
}

// With the weighted budget the view's PDFs are those of weighted values; a view whose keypoints
// all weigh 1 (fewer than the full-weight part of the budget) is described exactly as without it.
TEST(WeightedBudget, ViewsUnderTheBudgetAreDescribedAsBefore) {
  const Cloud view = sim::builtinBenchmarkView();
  DescriptorOptions hard;
  hard.iss.max_keypoints = 200;  // above what the view has
  hard.iss.fill_budget = false;   // (filled, K would be 200)
  DescriptorOptions soft = hard;
  soft.iss.budget_taper = 0.1;
  const ViewDescriptor a = describeView(view, hard), b = describeView(view, soft);
  ASSERT_LT(a.keypointCount(), 180);
  ASSERT_EQ(b.keypoint_weight.size(), static_cast<std::size_t>(b.keypointCount()));
  for (double w : b.keypoint_weight) ASSERT_EQ(w, 1.0);
  for (std::size_t f = 0; f < a.pdfs.size(); ++f)
    EXPECT_LT(l1Distance(a.pdfs[f], b.pdfs[f]), f == 2 ? 2e-3 : 1e-9) << featureName(a.features[f]);  // KPA3: the polynomial arccos
}

}  // namespace
}  // namespace keyturn
