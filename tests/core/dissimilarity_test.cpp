#include <gtest/gtest.h>

#include <cmath>

#include "keyturn/core/dissimilarity.h"
#include "keyturn/core/error.h"

using namespace keyturn;

namespace {
const std::vector<double> kP = {0.5, 0.5, 0.0, 0.0};
const std::vector<double> kQ = {0.0, 0.0, 0.5, 0.5};
const std::vector<double> kA = {0.25, 0.25, 0.25, 0.25};
const std::vector<double> kB = {0.1, 0.2, 0.3, 0.4};
}  // namespace

TEST(Dissimilarity, IdenticalPdfsAreZero) {
  for (auto d : {Dissimilarity::Bhattacharyya, Dissimilarity::ChiSquared, Dissimilarity::L1,
                 Dissimilarity::JensenShannon, Dissimilarity::Emd})
    EXPECT_NEAR(dissimilarity(d, kB, kB), 0.0, 1e-12);
  // A PDF of floats sums to 1 only within rounding; from itself it is still exactly 0.
  std::vector<double> f;
  for (int i = 0; i < 32; ++i) f.push_back(static_cast<float>(1.0 / (3 + i)));
  double sum = 0;
  for (double v : f) sum += v;
  for (double& v : f) v = static_cast<float>(v / sum);
  for (auto d : {Dissimilarity::Bhattacharyya, Dissimilarity::ChiSquared, Dissimilarity::L1,
                 Dissimilarity::JensenShannon, Dissimilarity::Emd})
    EXPECT_EQ(dissimilarity(d, f, f), 0.0) << static_cast<int>(d);
}

TEST(Dissimilarity, DisjointPdfsHitTheirMaxima) {
  EXPECT_DOUBLE_EQ(l1Distance(kP, kQ), 2.0);
  EXPECT_DOUBLE_EQ(chiSquared(kP, kQ), 1.0);
  EXPECT_NEAR(jensenShannon(kP, kQ), std::log(2.0), 1e-12);
  EXPECT_DOUBLE_EQ(bhattacharyya(kP, kQ), 50.0);
  // Mass moved by 2 bins of 4: EMD = (0.5 + 1 + 0.5) / 4.
  EXPECT_DOUBLE_EQ(emd1d(kP, kQ), 0.5);
}

TEST(Dissimilarity, KnownValuesOnOverlappingPdfs) {
  const double bc = std::sqrt(0.025) + std::sqrt(0.05) + std::sqrt(0.075) + std::sqrt(0.1);
  EXPECT_NEAR(bhattacharyya(kA, kB), -std::log(bc), 1e-12);
  EXPECT_NEAR(l1Distance(kA, kB), 0.4, 1e-12);
  const double chi = 0.5 * (0.0225 / 0.35 + 0.0025 / 0.45 + 0.0025 / 0.55 + 0.0225 / 0.65);
  EXPECT_NEAR(chiSquared(kA, kB), chi, 1e-12);
  // CDF differences 0.15, 0.2, 0.15, 0 → 0.5 / 4.
  EXPECT_NEAR(emd1d(kA, kB), 0.125, 1e-12);
  double js = 0;
  for (int i = 0; i < 4; ++i) {
    const double m = 0.5 * (kA[i] + kB[i]);
    js += 0.5 * kA[i] * std::log(kA[i] / m) + 0.5 * kB[i] * std::log(kB[i] / m);
  }
  EXPECT_NEAR(jensenShannon(kA, kB), js, 1e-12);
  EXPECT_NEAR(jensenShannon(kA, kB), jensenShannon(kB, kA), 1e-15);
}

TEST(Dissimilarity, MismatchedLengthsAreAnError) {
  EXPECT_THROW(l1Distance({1.0}, {0.5, 0.5}), Error);
  EXPECT_THROW(parseDissimilarity("cosine"), Error);
  EXPECT_EQ(parseDissimilarity("js"), Dissimilarity::JensenShannon);
}
