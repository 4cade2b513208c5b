// keyturn repeatability's option syntax (app/study_options.cpp): the lists --eps and --detectors
// take become the study's typed options, and their errors name the flag.
#include "study_options.h"

#include <gtest/gtest.h>

#include "support/error_of.h"

using namespace keyturn;
using namespace keyturn::app;
using keyturn::test::errorOf;

TEST(StudyOptions, EpsListsAreRangesOrListsOfPositiveMultiples) {
  EXPECT_EQ(parseEpsList("1:3:0.5"), (std::vector<double>{1, 1.5, 2, 2.5, 3}));
  // 0.1 added ten times is not 1.0: the range is START + i·STEP, so its end is kept.
  EXPECT_EQ(parseEpsList("0.1:1:0.1").size(), 10u);
  EXPECT_EQ(parseEpsList("0.5,2"), (std::vector<double>{0.5, 2}));
  EXPECT_EQ(errorOf([] { parseEpsList("1:x:1"); }), "--eps: 'x' is not a number");
  EXPECT_EQ(errorOf([] { parseEpsList("1.5x"); }), "--eps: '1.5x' is not a number");
  EXPECT_EQ(errorOf([] { parseEpsList("3:1:1"); }), "--eps: expected START:STOP:STEP with START <= STOP and STEP > 0, got '3:1:1'");
  EXPECT_EQ(errorOf([] { parseEpsList("-1,2"); }), "--eps: each ε must be a positive multiple of the resolution, got '-1,2'");
}

TEST(StudyOptions, DetectorListsNameEachDetector) {
  EXPECT_EQ(parseDetectorList("iss,uniform"), (std::vector<Detector>{Detector::Iss, Detector::Uniform}));
  EXPECT_EQ(errorOf([] { parseDetectorList(""); }), "--detectors: no detector named");
}
