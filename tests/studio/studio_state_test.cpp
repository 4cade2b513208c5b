// The studio's pieces that need no window (state and formatting): the stability
// of live recognition, the distance image's scale, a --object checked against
// the simulated objects.
#include <gtest/gtest.h>

#include <cmath>

#include "image_panel.h"
#include "keyturn/studio/studio_session.h"
#include "stability.h"

using namespace keyturn::studio;

TEST(Stability, IsTheShareAgreeingWithTheMostFrequentClass) {
  Stability s(4);
  EXPECT_EQ(s.mode(), -1);
  EXPECT_EQ(s.agreement(), 0.0);
  for (int l : {1, 2, 2, 3, 2}) s.add(l);  // window keeps 2, 2, 3, 2
  EXPECT_EQ(s.frames(), 4);
  EXPECT_EQ(s.mode(), 2);
  EXPECT_EQ(s.agreeing(), 3);
  EXPECT_DOUBLE_EQ(s.agreement(), 0.75);
  s.add(3);  // 2, 3, 2, 3: a tie goes to the newest
  EXPECT_EQ(s.mode(), 3);
  s.clear();
  EXPECT_EQ(s.frames(), 0);
}

TEST(DistanceImage, ScaleIsInMetresOverTheValidPixels) {
  // One pixel with no return, then 1000, 1020, …, 3000 counts at 1 mm per count:
  // the scale spans the valid pixels' 2nd to 98th percentile, in metres.
  std::vector<std::uint16_t> raw = {0};
  for (int v = 1000; v <= 3000; v += 20) raw.push_back(static_cast<std::uint16_t>(v));
  ImageScale scale;
  const QImage img = distanceImage(raw, static_cast<int>(raw.size()), 1, 0.001, &scale);
  EXPECT_EQ(img.size(), QSize(102, 1));
  EXPECT_EQ(img.pixelColor(0, 0), QColor(Qt::black));  // no return stays black
  EXPECT_NEAR(scale.lo, 1.04, 1e-9);
  EXPECT_NEAR(scale.hi, 2.96, 1e-9);
  EXPECT_EQ(scale.unit, QString("m"));
  EXPECT_NE(img.pixelColor(1, 0), img.pixelColor(101, 0));  // near and far differ
}

TEST(StudioSession, AnUnknownObjectIsNamedWithTheKnownOnes) {
  const std::vector<SimObject> objects = {{"mug", "ycb_025_mug", "m.ply"}, {"bowl", "ycb_024_bowl", "b.ply"}};
  EXPECT_EQ(unknownSimObject(objects, "ycb_024_bowl", "objects.csv"), "");
  EXPECT_EQ(unknownSimObject(objects, "drill", "objects.csv"),
            "--object drill: not in objects.csv (ycb_025_mug, ycb_024_bowl)");
}
