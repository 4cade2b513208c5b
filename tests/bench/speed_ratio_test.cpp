#include "keyturn/bench/speed_ratio.h"

#include <gtest/gtest.h>

#include <cmath>

using keyturn::bench::speedComparison;

TEST(SpeedComparison, FasterWhenOursIsShorter) {
  EXPECT_EQ(speedComparison(4.25, 18.1), "4.3× faster");
  EXPECT_EQ(speedComparison(1.0, 1.06), "1.1× faster");
}

TEST(SpeedComparison, SlowerWhenOursIsLonger) {
  // The case: keyturn 165 ms against PCL's 77 ms once printed "0.5× faster".
  EXPECT_EQ(speedComparison(165.0, 77.0), "2.1× slower");
  EXPECT_EQ(speedComparison(10.0, 7.0), "1.4× slower");
}

TEST(SpeedComparison, EvenAndMissingTimes) {
  EXPECT_EQ(speedComparison(10.0, 10.4), "about as fast");
  EXPECT_EQ(speedComparison(10.4, 10.0), "about as fast");
  EXPECT_EQ(speedComparison(0.0, 10.0), "not comparable (a time is missing)");
  EXPECT_EQ(speedComparison(10.0, NAN), "not comparable (a time is missing)");
}
