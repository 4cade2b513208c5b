// The set network over the keypoints (--classifier setnet, features "kpset"): it learns shapes from
// the keypoints' pairwise geometry, answers alike whatever the keypoints' order and the object's
// pose, round-trips through its file, and refuses inputs that are not a keypoint set.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>

#include "keyturn/core/error.h"
#include "keyturn/learning/classifier.h"
#include "keyturn/learning/keypoint_set.h"
#include "support/scratch_path.h"

using namespace keyturn;
using namespace keyturn::learning;

namespace {

// K points on one of three surfaces of about the same size (metres): 0 a sphere of radius 5 cm,
// 1 a cylinder's side (radius 3 cm, height 12 cm), 2 a flat 10 × 8 cm rectangle; 1 mm noise.
std::vector<Eigen::Vector3f> shapePoints(int shape, int k, std::mt19937& rng) {
  std::uniform_real_distribution<float> u(-1.f, 1.f);
  std::normal_distribution<float> noise(0.f, 0.001f);
  std::vector<Eigen::Vector3f> points;
  while (static_cast<int>(points.size()) < k) {
    Eigen::Vector3f p;
    if (shape == 0) {
      Eigen::Vector3f d(u(rng), u(rng), u(rng));
      if (d.norm() < 1e-3f || d.norm() > 1.f) continue;
      p = 0.05f * d.normalized();
    } else if (shape == 1) {
      const float a = 3.14159265f * u(rng);
      p = {0.03f * std::cos(a), 0.03f * std::sin(a), 0.06f * u(rng)};
    } else {
      p = {0.05f * u(rng), 0.04f * u(rng), 0.f};
    }
    points.push_back(p + Eigen::Vector3f(noise(rng), noise(rng), noise(rng)));
  }
  return points;
}

// The points turned by a random rotation and moved by up to a metre.
std::vector<Eigen::Vector3f> moved(std::vector<Eigen::Vector3f> points, std::mt19937& rng) {
  std::uniform_real_distribution<float> u(-1.f, 1.f);
  const Eigen::Quaternionf q = Eigen::Quaternionf(u(rng), u(rng), u(rng), u(rng)).normalized();
  const Eigen::Vector3f t(u(rng), u(rng), u(rng));
  for (auto& p : points) p = q * p + t;
  return points;
}

void putRow(Matrix& x, Eigen::Index r, const std::vector<Eigen::Vector3f>& points) {
  const std::vector<double> block = keypointSetBlock(points);
  for (std::size_t c = 0; c < block.size(); ++c) x(r, static_cast<Eigen::Index>(c)) = static_cast<float>(block[c]);
}

struct Sets {
  Matrix x;
  std::vector<int> y;
  std::vector<std::vector<Eigen::Vector3f>> points;
};

Sets makeSets(int per_class, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> count(12, kKeypointSetSize);
  Sets s;
  s.x.resize(3 * per_class, kKeypointSetWidth);
  for (int i = 0; i < 3 * per_class; ++i) {
    const int shape = i % 3;
    s.points.push_back(moved(shapePoints(shape, count(rng), rng), rng));
    putRow(s.x, i, s.points.back());
    s.y.push_back(shape);
  }
  return s;
}

ClassifierParams setnetParams() {
  ClassifierParams p;
  p.kind = "setnet";
  p.seed = 5;
  p.setnet.epochs = 25;
  p.setnet.min_steps = 0;  // the epochs as set (these sets are small)
  return p;
}

double accuracy(const Matrix& proba, const std::vector<int>& y) {
  const std::vector<int> got = argmaxRows(proba);
  int right = 0;
  for (std::size_t i = 0; i < y.size(); ++i) right += got[i] == y[i];
  return static_cast<double>(right) / static_cast<double>(y.size());
}

}  // namespace

TEST(KeypointSet, BlockHoldsKAndTheCentredKeypointsThenZeros) {
  const std::vector<double> b = keypointSetBlock({{1.f, 2.f, 3.f}, {3.f, 2.f, 1.f}, {2.f, 5.f, 2.f}});
  ASSERT_EQ(b.size(), static_cast<std::size_t>(1 + 3 * 64));
  EXPECT_EQ(b[0], 3.0);
  // Centroid (2, 3, 2).
  const std::vector<double> want = {-1, -1, 1, 1, -1, -1, 0, 2, 0};
  for (std::size_t i = 0; i < want.size(); ++i) EXPECT_NEAR(b[1 + i], want[i], 1e-6) << i;
  for (std::size_t i = 10; i < b.size(); ++i) ASSERT_EQ(b[i], 0.0) << i;
  std::vector<Eigen::Vector3f> many(70, Eigen::Vector3f(0.1f, 0.f, 0.f));
  EXPECT_EQ(keypointSetBlock(many)[0], 64.0) << "at most 64 keypoints";
  EXPECT_EQ(keypointSetBlock({})[0], 0.0);
  // 128 keypoints on a line, x = 0 … 127: every second one, 0, 2, … 126 (centroid 63), not the first 64.
  std::vector<Eigen::Vector3f> line;
  for (int i = 0; i < 128; ++i) line.emplace_back(static_cast<float>(i), 0.f, 0.f);
  const std::vector<double> strided = keypointSetBlock(line);
  for (int j = 0; j < 64; ++j) EXPECT_NEAR(strided[1 + 3 * j], 2.0 * j - 63.0, 1e-9) << j;
}

TEST(SetNetwork, LearnsShapesFromKeypointsInAnyPoseAndOrder) {
  const Sets train = makeSets(60, 1), test = makeSets(30, 2);
  auto clf = makeClassifier(setnetParams());
  clf->fit(train.x, train.y, 3);
  const Matrix p = clf->predictProba(test.x);
  ASSERT_EQ(p.rows(), test.x.rows());
  ASSERT_EQ(p.cols(), 3);
  for (Eigen::Index r = 0; r < p.rows(); ++r) EXPECT_NEAR(p.row(r).sum(), 1.f, 1e-5f);
  // Chance is 1/3; the three shapes differ in their pairwise distances and angles.
  EXPECT_GE(accuracy(p, test.y), 0.9);

  // The same keypoints in another order, turned and moved again: the same answer.
  std::mt19937 rng(9);
  Matrix again(test.x.rows(), kKeypointSetWidth);
  for (std::size_t i = 0; i < test.points.size(); ++i) {
    std::vector<Eigen::Vector3f> pts = test.points[i];
    std::shuffle(pts.begin(), pts.end(), rng);
    putRow(again, static_cast<Eigen::Index>(i), moved(pts, rng));
  }
  const Matrix q = clf->predictProba(again);
  EXPECT_LT((p - q).cwiseAbs().maxCoeff(), 2e-4f);
}

TEST(SetNetwork, SavedModelPredictsIdenticallyAndSameSeedSameModel) {
  const Sets train = makeSets(20, 3), test = makeSets(5, 4);
  ClassifierParams params = setnetParams();
  params.setnet.epochs = 3;
  auto a = makeClassifier(params), b = makeClassifier(params);
  a->fit(train.x, train.y, 3);
  b->fit(train.x, train.y, 3);
  const Matrix pa = a->predictProba(test.x);
  EXPECT_EQ(pa, b->predictProba(test.x));
  const keyturn::test::ScratchFolder scratch("set_network_file");
  std::filesystem::create_directories(scratch.path);
  const std::string file = (scratch.path / "model.pt").string();
  a->save(file);
  auto loaded = makeClassifier(params);
  loaded->load(file, kKeypointSetWidth, 3);
  EXPECT_EQ(loaded->predictProba(test.x), pa);
  try {
    makeClassifier(params)->load(file, kKeypointSetWidth, 4);
    ADD_FAILURE() << "a network of 3 classes loaded as one of 4";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("3 classes; its sidecar says"), std::string::npos) << e.what();
  }
}

// Rows a cache can hold for a view gone wrong: no keypoints, NaN (not described), a K past the block,
// coordinates of 1e30. Each gets probabilities, not NaN.
TEST(SetNetwork, BrokenRowsGetProbabilities) {
  const Sets train = makeSets(10, 6);
  ClassifierParams params = setnetParams();
  params.setnet.epochs = 2;
  auto clf = makeClassifier(params);
  clf->fit(train.x, train.y, 3);
  Matrix x = Matrix::Zero(4, kKeypointSetWidth);
  x.row(1).setConstant(std::nanf(""));
  x(2, 0) = 1000.f;
  x.row(2).tail(kKeypointSetWidth - 1).setConstant(0.01f);
  x(3, 0) = 5.f;
  x.row(3).segment(1, 15).setConstant(1e30f);
  x(3, 1) = -1e30f;
  const Matrix p = clf->predictProba(x);
  ASSERT_EQ(p.rows(), 4);
  for (Eigen::Index r = 0; r < 4; ++r) {
    EXPECT_TRUE(p.row(r).allFinite()) << r;
    EXPECT_NEAR(p.row(r).sum(), 1.f, 1e-5f) << r;
  }
  EXPECT_EQ(clf->predictProba(Matrix(0, kKeypointSetWidth)).rows(), 0);
}

TEST(SetNetwork, FeaturesWithoutTheKeypointsAreOneLine) {
  Matrix x = Matrix::Ones(6, 32);
  try {
    makeClassifier(setnetParams())->fit(x, {0, 1, 0, 1, 0, 1}, 2);
    ADD_FAILURE() << "32 PDF bins trained as keypoints";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()),
              "set network: 32 feature columns; it needs the keypoints first (features 'kpset' or 'kpset+…', 193 "
              "values)");
  }
}

// Further blocks after the keypoints reach the head standardised: a class told only by them is learnt.
TEST(SetNetwork, BlocksAfterTheKeypointsAreUsed) {
  std::mt19937 rng(4);
  const int n = 120;
  Matrix x(n, kKeypointSetWidth + 1);
  std::vector<int> y;
  for (int i = 0; i < n; ++i) {
    putRow(x, i, moved(shapePoints(0, 30, rng), rng));  // every row the same shape
    y.push_back(i % 2);
    x(i, kKeypointSetWidth) = 100.f + (i % 2 ? 5.f : -5.f) + std::normal_distribution<float>(0.f, 1.f)(rng);
  }
  ClassifierParams params = setnetParams();
  params.setnet.epochs = 10;
  auto clf = makeClassifier(params);
  clf->fit(x, y, 2);
  EXPECT_GE(accuracy(clf->predictProba(x), y), 0.95);
}
