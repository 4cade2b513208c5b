#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "keyturn/core/median.h"

using namespace keyturn;

// Values worked by hand: sorted, {1, 2, 7, 9} has middle values 2 and 7.
TEST(Median, AnOddCountGivesItsMiddleValueEitherWay) {
  EXPECT_EQ(upperMedian(std::vector<double>{9, 1, 7, 2, 5}), 5.0);
  EXPECT_EQ(median(std::vector<double>{9, 1, 7, 2, 5}), 5.0);
}

TEST(Median, AnEvenCountGivesTheUpperMiddleValueOrTheMeanOfBoth) {
  EXPECT_EQ(upperMedian(std::vector<double>{9, 1, 7, 2}), 7.0);  // one of the values, not a blend
  EXPECT_EQ(median(std::vector<double>{9, 1, 7, 2}), 4.5);
}

TEST(Median, NonFiniteValuesAreLeftOut) {
  const double nan = std::nan(""), inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(upperMedian(std::vector<double>{nan, 3, inf, 1, -inf, 2}), 2.0);
  EXPECT_EQ(median(std::vector<double>{nan, 4, 1, inf}), 2.5);
  EXPECT_EQ(upperMedian(std::vector<float>{std::nanf(""), 0.5f, 0.25f}), 0.5f);
}

TEST(Median, NoValueLeftIsNaNNotACrash) {
  EXPECT_TRUE(std::isnan(upperMedian(std::vector<double>{})));
  EXPECT_TRUE(std::isnan(median(std::vector<double>{std::nan("")})));
  EXPECT_TRUE(std::isnan(upperMedian(std::vector<float>{std::numeric_limits<float>::infinity()})));
}
