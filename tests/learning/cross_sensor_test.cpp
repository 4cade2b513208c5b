// Across sensors (evaluate --protocol cross-sensor): a camera that moves every class's signal
// elsewhere defeats a model trained on the other camera alone and not one trained on both; every
// cell is a held-out elevation's views, counted per camera.
#include <gtest/gtest.h>

#include "keyturn/learning/cross_sensor_evaluation.h"
#include "support/error_of.h"

using namespace keyturn::learning;
using keyturn::test::errorOf;

namespace {

constexpr int kClasses = 4, kViews = 12;

// Camera 0: class k lights value k of an 8-value block. Camera 1 (the same view ids): class k
// lights value (k + 1) mod 4 — what camera 0 shows of class k + 1 — and marks itself in value 4 + k.
FeatureTable cameraViews(int camera, const std::vector<std::string>& elevations) {
  FeatureTable t;
  t.blocks = {"kpd2"};
  t.sizes = {8};
  t.spec = {{"bins", "8"}};
  for (const auto& e : elevations)
    for (int k = 0; k < kClasses; ++k)
      for (int v = 0; v < kViews; ++v) {
        FeatureRow r;
        r.cls = "c";
        r.instance = std::string(1, static_cast<char>('a' + k));
        r.elevation = e;
        r.id = "c/" + r.instance + "/e" + e + "/a" + std::to_string(v * 30);
        r.keypoints = 30;
        // Exactly 0 and 1, no noise: XGBoost splits at training values, so a test value just
        // beyond every training one falls on the other side by chance; this tests the folds.
        r.values.assign(8, 0.f);
        r.values[static_cast<std::size_t>(camera == 0 ? k : (k + 1) % kClasses)] = 1.f;
        if (camera == 1) r.values[static_cast<std::size_t>(4 + k)] = 1.f;
        t.rows.push_back(r);
      }
  return t;
}

const CrossSensorCell& cell(const CrossSensorResult& r, CrossSensorTraining trained, int tested) {
  for (const auto& c : r.cells)
    if (c.trained == trained && c.tested == tested) return c;
  throw std::runtime_error("no such cell");
}

}  // namespace

TEST(CrossSensor, ASingleCameraModelFailsTheOtherCameraAndOneTrainedOnBothDoesNot) {
  const std::vector<std::string> elevations = {"30", "45", "60"};
  const CrossSensorData data = crossSensorData(cameraViews(0, elevations), cameraViews(1, elevations), {"tof", "kinect"});
  ASSERT_EQ(data.first_rows, 3u * kClasses * kViews);
  ASSERT_EQ(data.table.rows.size(), 2 * data.first_rows);
  CrossSensorOptions o;
  o.feature_sets = {"kpd2"};
  o.classifiers = {"xgboost"};
  o.jobs = 2;
  EXPECT_EQ(crossSensorTrainings(data, o), 9u) << "3 trainings (first, second, both) × 3 elevations left out";
  std::size_t trainings = 0;
  const CrossSensorResult r = evaluateCrossSensor(data, o, [&] { ++trainings; });
  EXPECT_EQ(trainings, 9u);
  EXPECT_EQ(r.elevations, elevations);
  ASSERT_EQ(r.cells.size(), 6u);
  for (const auto& c : r.cells) {
    EXPECT_EQ(c.views, 3u * kClasses * kViews) << "every view of a camera tested once, at its left-out elevation";
    EXPECT_EQ(c.fold_accuracy.size(), 3u);
  }
  EXPECT_EQ(cell(r, CrossSensorTraining::First, 0).accuracy(), 1.0);
  EXPECT_EQ(cell(r, CrossSensorTraining::First, 1).accuracy(), 0.0) << "camera 1 shows class k as camera 0's k + 1";
  EXPECT_EQ(cell(r, CrossSensorTraining::Second, 1).accuracy(), 1.0);
  EXPECT_EQ(cell(r, CrossSensorTraining::Both, 0).accuracy(), 1.0);
  EXPECT_EQ(cell(r, CrossSensorTraining::Both, 1).accuracy(), 1.0);

  const CrossSensorReport rep = crossSensorReport(r, data, {"ds/tof", "ds/kinect"});
  EXPECT_NE(rep.markdown.find("| kpd2 | xgboost | tof | 100.0 | 0.0 | 100.0 |"), std::string::npos) << rep.markdown;
  EXPECT_NE(rep.markdown.find("| kpd2 | xgboost | both | 100.0 | 100.0 | 0.0 |"), std::string::npos) << rep.markdown;
  EXPECT_NE(rep.csv.find("kpd2,xgboost,tof,kinect,144,0,0.0\n"), std::string::npos) << rep.csv;
  ASSERT_EQ(rep.plots.curves.size(), 1u);
  EXPECT_EQ(rep.plots.curves[0].x_categories,
            (std::vector<std::string>{"1 → 1", "1 → 2", "2 → 1", "2 → 2", "both → 1", "both → 2"}));
  EXPECT_EQ(rep.plots.curves[0].x_label, "trained on → tested on (1: tof, 2: kinect)");
  EXPECT_EQ(rep.plots.curves[0].series[0].y, (std::vector<double>{100, 0, cell(r, CrossSensorTraining::Second, 0).accuracy() * 100, 100, 100, 100}));
}

TEST(CrossSensor, BadPairsAreNamed) {
  EXPECT_EQ(errorOf([] { crossSensorData(cameraViews(0, {"30"}), cameraViews(1, {"30"}), {"tof", "kinect"}); }),
            "tof: cross-sensor leaves one elevation out at a time, and its views have one (30)");
  FeatureTable other = cameraViews(1, {"30", "45"});
  other.rows[0].id = "c/z/e30/a0";
  EXPECT_EQ(errorOf([&] { crossSensorData(cameraViews(0, {"30", "45"}), other, {"tof", "kinect"}); }),
            "kinect: view c/z/e30/a0 is not a view of the dataset");
}
