// keyturn studio against the simulated rig, through the real drivers, and against a recording played
// back: connect, live recognition, a short capture sequence, pause, a pulled cable, settings.
// Runs under xvfb-run (the 3D view needs an OpenGL context).
#include <QAction>
#include <QCheckBox>
#include <QComboBox>
#include <QDir>
#include <QDoubleSpinBox>
#include <QFile>
#include <QJsonDocument>
#include <QJsonObject>
#include <QLabel>
#include <QListWidget>
#include <QLineEdit>
#include <QPushButton>
#include <QScrollArea>
#include <QScopeGuard>
#include <QScrollBar>
#include <QSet>
#include <QtTest>

#include <algorithm>
#include <cmath>
#include <atomic>
#include <condition_variable>
#include <limits>
#include <map>
#include <mutex>
#include <utility>

#include "devices_panel.h"
#include "keyturn/dataset/dataset.h"
#include "keyturn/learning/recognizer.h"
#include "keyturn/rig/dataset_playback.h"
#include "keyturn/rig/dataset_simulation.h"
#include "keyturn/dataset/sidecars.h"
#include "keyturn/learning/model_predictions.h"
#include "keyturn/studio/studio_window.h"
#include "keyturn/studio/studio_rig_factory.h"
#include "support/scratch_path.h"

using namespace keyturn;

namespace {
// The waits' limits, longer where the build is slower (ASan + UBSan: KEYTURN_TEST_TIME_SCALE=3). Each
// wait ends as soon as its condition holds; only a failing one waits this long.
int waitMs(int ms) {
  static const int scale = std::max(1, qEnvironmentVariableIntValue("KEYTURN_TEST_TIME_SCALE"));
  return ms * scale;
}
}  // namespace
using namespace keyturn::studio;

namespace {
// How many frames a camera may acquire: a test that needs every frame recognised lets the next one
// through only after the last one's result arrived (no frame dropped, whatever the machine's load).
class FrameGate {
 public:
  void allow(long frames) {
    {
      std::lock_guard<std::mutex> l(mutex_);
      allowed_ = frames;
    }
    opened_.notify_all();
  }
  void open() { allow(std::numeric_limits<long>::max()); }
  void waitToAcquire(long acquired) {
    std::unique_lock<std::mutex> l(mutex_);
    opened_.wait(l, [&] { return acquired < allowed_; });
  }

 private:
  std::mutex mutex_;
  std::condition_variable opened_;
  long allowed_ = std::numeric_limits<long>::max();
};

// Counts the frames a camera delivers, so a test waits on frames rather than on the clock.
class CountedCamera final : public drivers::TofCamera {
 public:
  CountedCamera(std::unique_ptr<drivers::TofCamera> camera, std::atomic<long>& acquired, FrameGate& gate)
      : camera_(std::move(camera)), acquired_(acquired), gate_(gate) {}
  void configure(const drivers::TofSettings& s) override { camera_->configure(s); }
  drivers::TofSettings settings() const override { return camera_->settings(); }
  drivers::TofFrame acquire() override {
    gate_.waitToAcquire(acquired_);
    drivers::TofFrame f = camera_->acquire();
    ++acquired_;
    return f;
  }
  std::string deviceString() const override { return camera_->deviceString(); }
  std::uint32_t serial() const override { return camera_->serial(); }

 private:
  std::unique_ptr<drivers::TofCamera> camera_;
  std::atomic<long>& acquired_;
  FrameGate& gate_;
};

// The studio's own devices, observed: frames acquired and camera opens counted, and the USB bus
// replaced (cameras are plugged in and out by the test, and the bus reports a change as the
// libusb hot-plug watcher does, its polls counted).
class ObservedFactory final : public RigFactory {
 public:
  explicit ObservedFactory(RigFactory& real) : real_(real) {}
  void plug(std::vector<rig::FoundCamera> cameras) {
    cameras_ = std::move(cameras);
    changed_ = true;
  }
  int scans = 0, polls = 0;
  std::atomic<long> acquired{0}, opens{0};
  FrameGate gate;  // open unless a test closes it

  std::unique_ptr<drivers::TofCamera> openCamera(const rig::CameraSpec& r, Log log) override {
    ++opens;
    return std::make_unique<CountedCamera>(real_.openCamera(r, std::move(log)), acquired, gate);
  }
  std::unique_ptr<drivers::PoseSource> openPose(const rig::PoseSpec& r, Log log) override {
    return real_.openPose(r, std::move(log));
  }
  std::vector<SimObject> simObjects() const override { return real_.simObjects(); }
  rig::CameraSpec simulatedCamera(const std::string& sim_object) override { return real_.simulatedCamera(sim_object); }
  void setSimulatedCameraUnplugged(bool unplugged) override { real_.setSimulatedCameraUnplugged(unplugged); }
  std::vector<rig::FoundCamera> usbCameras() override {
    ++scans;
    return cameras_;
  }
  bool usbCamerasChanged() override {
    ++polls;
    return std::exchange(changed_, false);
  }

 private:
  RigFactory& real_;
  std::vector<rig::FoundCamera> cameras_;
  bool changed_ = false;
};

// After `frames` more frames than `since` were acquired, every one of them has reached the window
// (a frame is sent before the next acquisition starts): deliver what is queued.
bool framesDelivered(ObservedFactory& f, long since, long frames) {
  if (f.acquired < since + frames + 1) return false;
  QCoreApplication::processEvents();
  return true;
}
}  // namespace

class StudioTest : public QObject {
  Q_OBJECT

 private:
  // First: removed after the factory and the windows, which write into it, are gone.
  const keyturn::test::ScratchFolder scratch_{"studio_test"};
  std::unique_ptr<StudioRigFactory> factory_;

  // NAME in the test's scratch folder.
  QString file(const QString& name) const {
    return QString::fromStdString((scratch_.made() / name.toStdString()).string());
  }

  // A small recording of the power drill (12 views at 30°, every 30°), made on the simulated rig.
  QString recording_;

  StudioOptions playback(double rate_fps) {
    StudioOptions o;
    o.playback = {recording_.toStdString(), rate_fps, true};
    o.model = std::string(KEYTURN_DATA_DIR) + "/models/sim-objects";
    o.settings_file = file("playback.ini").toStdString();
    return o;
  }

  // The built-in model's open-set settings as its file states them (model.json's "open_set").
  static QJsonObject builtInOpenSet() {
    QFile model(QString(KEYTURN_DATA_DIR) + "/models/sim-objects/model.json");
    if (!model.open(QIODevice::ReadOnly)) return {};
    return QJsonDocument::fromJson(model.readAll()).object()["open_set"].toObject();
  }

  StudioOptions simulated(const std::string& object) {
    StudioOptions o;
    o.simulated = true;
    o.sim_object = object;
    o.model = std::string(KEYTURN_DATA_DIR) + "/models/sim-objects";
    o.settings_file = file("studio.ini").toStdString();
    return o;
  }

 private slots:
  void initTestCase() {
    recording_ = file("recording");
    rig::DatasetSimulation sim;
    sim.out = recording_.toStdString();
    sim.objects = {{"drill", "ycb_035_power_drill", std::string(KEYTURN_DATA_DIR) + "/objects/drill__ycb_035_power_drill.ply"}};
    sim.elevations = {30};
    sim.step_deg = 30;
    QCOMPARE(rig::simulateDataset(sim).written, std::size_t(12));
  }
  // The 27 objects the studio's simulated turntable offers: the built-in model knows 15 of them.
  void init() { factory_ = std::make_unique<StudioRigFactory>(std::string(KEYTURN_DATA_DIR) + "/objects/objects-27.csv"); }
  void cleanup() { factory_.reset(); }

  void connectsAndShowsLiveFramesAndTheirCloud() {
    StudioWindow w(*factory_, simulated("ycb_025_mug"));
    w.show();
    QTRY_VERIFY_WITH_TIMEOUT(w.rates().frames > 30, waitMs(15000));
    QTRY_VERIFY_WITH_TIMEOUT(w.rates().results > 10, waitMs(15000));
    auto* angle = w.findChild<QLabel*>("poseAngle");
    QVERIFY(angle);
    QTRY_COMPARE_WITH_TIMEOUT(angle->text(), QString("0.00°"), waitMs(5000));
    auto* k = w.findChild<QLabel*>("keypointCount");
    QVERIFY(k);
    QTRY_VERIFY_WITH_TIMEOUT(k->text().startsWith("K = "), waitMs(5000));
    QVERIFY2(w.bannerText().isEmpty(), qPrintable(w.bannerText()));
  }

  void recognisesTheObjectOnTheSimulatedTurntable() {
    // The live path (the recogniser) and the model's training (the feature cache) describe a frame the
    // same way: this test caught the cache skipping the filter (a model trained on frames with their table).
    // The cameras' noise is drawn once per turntable angle: on the still table every frame is the same
    // view, so the live verdict is the model's answer on that one view, on every frame, and equals what
    // `keyturn classify` answers for the frame saved by Snapshot. (With a draw per frame the bowl was
    // unknown on 4 of 48 frames at 0°, and the agreement bar had sunk to 0.7; issue 51.)
    factory_.reset();  // one studio runtime folder per process
    factory_ = std::make_unique<StudioRigFactory>(std::string(KEYTURN_DATA_DIR) + "/objects/objects-27.csv",
                                                  /*noise_per_pose=*/true);
    const std::string model_dir = std::string(KEYTURN_DATA_DIR) + "/models/sim-objects";
    const learning::Model model = learning::loadModel(model_dir);
    for (const char* object : {"ycb_035_power_drill", "ycb_024_bowl"}) {
      StudioOptions o = simulated(object);
      o.dataset = file(QString("still-") + object).toStdString();
      StudioWindow w(*factory_, o);
      w.show();
      QTRY_VERIFY_WITH_TIMEOUT(w.rates().results >= 20, waitMs(20000));
      QVERIFY2(w.recognisedAgreement() == 1.0, qPrintable(QString::number(w.recognisedAgreement())));
      QAction* snapshot = nullptr;
      for (QAction* a : w.findChildren<QAction*>())
        if (a->text() == "Snapshot") snapshot = a;
      QVERIFY(snapshot);
      snapshot->trigger();
      const QDir snaps(QString::fromStdString(o.dataset) + "/snapshots");
      const QStringList pcds = snaps.entryList({"*.pcd"}, QDir::Files);
      QCOMPARE(pcds.size(), 1);
      learning::LabelledView view;
      view.id = view.path = snaps.filePath(pcds[0]).toStdString();
      const learning::FeatureTable t = learning::describeForModel(model, {view}, 1, nullptr, model_dir);
      const auto batch = learning::predictRows(model, t, model_dir);
      QCOMPARE(batch.size(), std::size_t(1));
      const QString answer = QString::fromStdString(learning::answerLabel(model.info, batch[0]));
      QCOMPARE(w.recognisedClass(), answer);
      // The drill's view is named; the bowl's is whatever the model answers on that one view, live and
      // batch alike (unknown with the model before 2026-12-07: one of the bowl's 4 in 48 frames at 0°).
      if (std::string(object) == "ycb_035_power_drill") QCOMPARE(answer, QString(object));
      if (batch[0].answer != learning::Answer::Class) continue;
      auto* legend = w.findChild<QLabel*>("pdfLegend");  // the chart's series, named above it
      QVERIFY(legend);
      QTRY_VERIFY2_WITH_TIMEOUT(legend->text().contains(QString("mean of %1").arg(answer)), qPrintable(legend->text()),
                                waitMs(5000));
    }
  }

  // Issue 34: an object the built-in model never saw (the scissors) is "unknown", for this view and
  // for the turn, while its classifier alone names a trained class.
  void anObjectTheBuiltInModelNeverSawIsUnknown() {
    StudioWindow w(*factory_, simulated("ycb_037_scissors"));
    w.show();
    QTRY_VERIFY_WITH_TIMEOUT(w.rates().results >= 20, waitMs(20000));
    QTRY_COMPARE_WITH_TIMEOUT(w.recognisedClass(), QString("unknown"), waitMs(10000));
    QTRY_COMPARE_WITH_TIMEOUT(w.fusedClass(), QString("unknown"), waitMs(10000));
    auto* verdict = w.findChild<QLabel*>("verdict");
    QVERIFY(verdict);
    // Its score under the threshold the built-in model's file states (0.40 with issue 47's first
    // model, 0.28 since its open set measures the χ² distance and since the filled budget, 0.277).
    const double threshold = builtInOpenSet()["threshold"].toDouble();
    QVERIFY2(threshold > 0.2 && threshold < 0.5, qPrintable(QString::number(threshold)));
    QVERIFY2(verdict->text().contains(" &lt; " + QString::number(threshold, 'f', 2)), qPrintable(verdict->text()));
    QVERIFY(verdict->toolTip().contains("last 20 frames"));  // which part is the verdict, which this frame's test
  }

  // Issue 34: the belief fused over the views of the table's turn, beside the single view's. At
  // rest it holds one view however many frames come (the newest: the bowl's first frame may be
  // unknown alone, 14 % of its frames are); a turn adds the views it brings (one per 5° bin); the
  // finished turn's belief stays; another object starts it again.
  // A half turn: seen end-on (65°-105°) the drill shows 4-29 keypoints and its single views score
  // under the threshold, so a quarter turn's answer rests on how many views a machine's recognition
  // rate brings (CI's 6 views over 0°-90° read "unknown" by the former vote; the turn threshold's
  // mean names it on 96-99 % of 6-view samples, docs/results.md "Fused turns"). Over 0°-180° every
  // sample of 4 or more of the drill's simulated views is named.
  void theFusedBeliefFollowsTheTurningTable() {
    StudioWindow w(*factory_, simulated("ycb_035_power_drill"));
    w.show();
    auto* angle = w.findChild<QLabel*>("poseAngle");
    QTRY_COMPARE_WITH_TIMEOUT(angle->text(), QString("0.00°"), waitMs(15000));
    QTRY_COMPARE_WITH_TIMEOUT(w.fusedViews(), 1, waitMs(20000));
    const long results = w.rates().results;
    QTRY_VERIFY_WITH_TIMEOUT(w.rates().results > results + 10, waitMs(15000));
    QCOMPARE(w.fusedViews(), 1);  // ten more results of the same view: still one view
    auto* fused = w.findChild<QLabel*>("fusedVerdict");
    QVERIFY(fused);
    QVERIFY2(fused->text().contains("· 1 view, 0°"), qPrintable(fused->text()));
    // The built-in model holds pose references and open-set answers, and says so.
    const auto info = w.findChildren<QLabel*>();
    const QString stated = QString("open-set: %1 at %2 %")  // the method and rate its file states (knn-relative, 5 %: data/models/README.md)
                               .arg(builtInOpenSet()["method"].toString())
                               .arg(std::lround(100 * builtInOpenSet()["false_accept"].toDouble()));
    QVERIFY2(stated == "open-set: knn-relative at 5 %", qPrintable(stated));
    QVERIFY(std::any_of(info.begin(), info.end(), [&](QLabel* l) {
      return l->text().contains(stated) && l->text().contains("fuses by pose");
    }));
    w.findChild<QDoubleSpinBox*>("poseTarget")->setValue(180);
    QTest::mouseClick(w.findChild<QPushButton*>("poseMoveTo"), Qt::LeftButton);
    QTRY_VERIFY_WITH_TIMEOUT(std::abs(angle->text().chopped(1).toDouble() - 180) < 0.2, waitMs(15000));
    const long arrived = w.rates().results;  // the frames taken before the table settled, recognised
    QTRY_VERIFY_WITH_TIMEOUT(w.rates().results > arrived + 10, waitMs(15000));
    QVERIFY2(w.fusedViews() >= 4, qPrintable(QString::number(w.fusedViews())));
    const int turned = w.fusedViews();
    QVERIFY2(turned <= 37, qPrintable(QString::number(turned)));  // at most one per 5° bin from 0° to 180°
    QVERIFY2(fused->text().contains(QString("· %1 views, ").arg(turned)), qPrintable(fused->text()));
    QVERIFY2(fused->toolTip().contains(QString("ycb_035_power_drill")) && fused->toolTip().contains(QString("· %1 views, ").arg(turned)),
             qPrintable(fused->toolTip()));  // whole where the line is cut
    QCOMPARE(w.fusedClass(), QString("ycb_035_power_drill"));
    QVERIFY2(w.fusedBelief() > 0.5, qPrintable(QString::number(w.fusedBelief())));
    // At rest again: the turn's belief stays.
    const long after = w.rates().results;
    QTRY_VERIFY_WITH_TIMEOUT(w.rates().results > after + 10, waitMs(15000));
    QCOMPARE(w.fusedViews(), turned);
    // Another object on the table: the sequence starts again, and fuses the bowl.
    auto* object = w.findChild<QComboBox*>("simObject");
    object->setCurrentIndex(object->findData("ycb_024_bowl"));
    QTRY_VERIFY_WITH_TIMEOUT(w.fusedViews() <= 1, waitMs(5000));
    auto* connect = w.findChild<QPushButton*>("cameraConnect");
    QTest::mouseClick(connect, Qt::LeftButton);  // disconnect, then connect the new object
    QTRY_COMPARE_WITH_TIMEOUT(connect->text(), QString("Connect"), waitMs(5000));
    QTest::mouseClick(connect, Qt::LeftButton);
    QTRY_COMPARE_WITH_TIMEOUT(w.fusedClass(), QString("ycb_024_bowl"), waitMs(20000));
    QCOMPARE(w.fusedViews(), 1);
  }

  void capturesAShortSequenceThatVerifies() {
    const QString dataset = file("captured");
    StudioOptions o = simulated("ycb_025_mug");
    o.dataset = dataset.toStdString();
    StudioWindow w(*factory_, o);
    w.show();
    QTRY_VERIFY_WITH_TIMEOUT(w.rates().frames > 5, waitMs(15000));
    auto* angle = w.findChild<QLabel*>("poseAngle");
    QTRY_VERIFY_WITH_TIMEOUT(angle->text().endsWith("°"), waitMs(5000));  // the turntable is connected
    w.findChild<QDoubleSpinBox*>("captureRange")->setValue(15);
    w.findChild<QDoubleSpinBox*>("captureStep")->setValue(5);
    QTest::mouseClick(w.findChild<QPushButton*>("captureStart"), Qt::LeftButton);
    auto* eta = w.findChild<QLabel*>("captureEta");
    QTRY_VERIFY_WITH_TIMEOUT(eta->text().startsWith("done"), waitMs(30000));
    QCOMPARE(eta->text(), QString("done: 3 views written, 0 were already there"));
    QCOMPARE(w.findChild<QListWidget*>("captureThumbnails")->count(), 3);
    const auto views = dataset::Dataset::readManifest(dataset.toStdString());
    QCOMPARE(views.size(), std::size_t(3));
    for (std::size_t i = 0; i < views.size(); ++i) {
      QCOMPARE(views[i].key.cls, std::string("mug"));
      QCOMPARE(views[i].key.instance, std::string("ycb_025_mug"));
      QCOMPARE(views[i].key.commanded_deg, 5.0 * static_cast<double>(i));
      QVERIFY(std::abs(views[i].measured_deg - 5.0 * static_cast<double>(i)) < 0.2);
    }
    const auto report = dataset::Dataset::verify(dataset.toStdString());
    QVERIFY(report.ok());
    QVERIFY(QFile::exists(dataset + "/mug/ycb_025_mug/e30/a10.0_distance.png"));
  }

  void anAxisCalibrationGoesIntoEveryViewAndTheDataset() {
    const QString dataset = file("calibrated");
    StudioOptions o = simulated("ycb_025_mug");
    o.dataset = dataset.toStdString();
    StudioWindow w(*factory_, o);
    w.show();
    QTRY_VERIFY_WITH_TIMEOUT(w.findChild<QLabel*>("poseAngle")->text().endsWith("°"), waitMs(15000));
    QTRY_VERIFY_WITH_TIMEOUT(w.rates().frames > 5, waitMs(15000));
    w.findChild<QDoubleSpinBox*>("captureRange")->setValue(10);  // 2 views
    auto* calibration = w.findChild<QLineEdit*>("captureCalibration");
    auto* start = w.findChild<QPushButton*>("captureStart");
    auto* eta = w.findChild<QLabel*>("captureEta");
    // A file that is not a calibration: refused, named, nothing captured.
    const QString bad = file("bad.json");
    QFile(bad).open(QIODevice::WriteOnly);
    calibration->setText(bad);
    QTest::mouseClick(start, Qt::LeftButton);
    QTRY_VERIFY_WITH_TIMEOUT(eta->text().contains("capture failed"), waitMs(5000));
    QVERIFY2(eta->text().contains(bad), qPrintable(eta->text()));
    QVERIFY(!QFile::exists(dataset + "/manifest.csv"));
    // A measured axis: camera 0.8 m in front of the table, turned; every view gets it composed
    // with its turntable angle.
    const QString good = file("axis.json");
    QFile f(good);
    QVERIFY(f.open(QIODevice::WriteOnly));
    f.write(R"({"format": "keyturn-axis-calibration", "version": 1,
               "camera_from_turntable": [[1,0,0,0.01],[0,0,-1,0.05],[0,1,0,0.8],[0,0,0,1]]})");
    f.close();
    calibration->setText(good);
    QTest::mouseClick(start, Qt::LeftButton);
    QTRY_VERIFY_WITH_TIMEOUT(eta->text().startsWith("done"), waitMs(30000));
    QVERIFY(QFile::exists(dataset + "/calibration.json"));
    const auto views = dataset::Dataset::readManifest(dataset.toStdString());
    QCOMPARE(views.size(), std::size_t(2));
    const auto t5 = dataset::readViewTransform((dataset + "/mug/ycb_025_mug/e30/a5.0.json").toStdString());
    QVERIFY(t5.has_value());
    QVERIFY(std::abs((*t5)(2, 3) - 0.8) < 1e-9);  // the calibration's translation
    const double a = views[1].measured_deg * M_PI / 180.0;
    QVERIFY2(std::abs((*t5)(0, 0) - std::cos(a)) < 1e-9, qPrintable(QString::number((*t5)(0, 0))));
  }

  void pauseFreezesTheLiveViewAndSnapshotSavesTheFrame() {
    const QString dataset = file("snap");
    ObservedFactory observed(*factory_);
    StudioOptions o = playback(50);
    o.dataset = dataset.toStdString();
    StudioWindow w(observed, o);
    w.show();
    QTRY_VERIFY_WITH_TIMEOUT(w.rates().frames > 5, waitMs(15000));
    QAction* pause = nullptr;
    QAction* snapshot = nullptr;
    for (QAction* a : w.findChildren<QAction*>()) {
      if (a->text() == "Pause live view") pause = a;
      if (a->text() == "Snapshot") snapshot = a;
    }
    QVERIFY(pause && snapshot);
    snapshot->trigger();
    const QDir snaps(dataset + "/snapshots");
    QCOMPARE(snaps.entryList({"*.pcd"}, QDir::Files).size(), 1);
    QCOMPARE(snaps.entryList({"*.png"}, QDir::Files).size(), 3);  // distance, amplitude, confidence
    pause->trigger();
    // Paused, the window takes none of the next 20 frames the camera delivers (nor any queued before).
    const long frozen = w.rates().frames;
    const long acquired = observed.acquired;
    QTRY_VERIFY_WITH_TIMEOUT(framesDelivered(observed, acquired, 20), waitMs(10000));
    QCOMPARE(w.rates().frames, frozen);
    pause->trigger();
    QTRY_VERIFY_WITH_TIMEOUT(w.rates().frames > frozen + 10, waitMs(10000));
  }

  void aPausedCaptureResumesWithTheMissingViewsOnly() {
    const QString dataset = file("paused");
    StudioOptions o = simulated("ycb_025_mug");
    o.dataset = dataset.toStdString();
    StudioWindow w(*factory_, o);
    w.show();
    QTRY_VERIFY_WITH_TIMEOUT(w.findChild<QLabel*>("poseAngle")->text().endsWith("°"), waitMs(15000));
    w.findChild<QDoubleSpinBox*>("captureRange")->setValue(30);  // 6 views
    auto* start = w.findChild<QPushButton*>("captureStart");
    QTest::mouseClick(start, Qt::LeftButton);
    auto* thumbs = w.findChild<QListWidget*>("captureThumbnails");
    QTRY_VERIFY_WITH_TIMEOUT(thumbs->count() >= 1, waitMs(20000));
    QTest::mouseClick(w.findChild<QPushButton*>("capturePause"), Qt::LeftButton);
    auto* eta = w.findChild<QLabel*>("captureEta");
    QTRY_VERIFY_WITH_TIMEOUT(eta->text().startsWith("paused"), waitMs(20000));
    const std::size_t before = dataset::Dataset::readManifest(dataset.toStdString()).size();
    QVERIFY(before >= 1 && before < 6);
    QCOMPARE(start->text(), QString("Resume"));
    QTest::mouseClick(start, Qt::LeftButton);
    QTRY_VERIFY_WITH_TIMEOUT(eta->text().startsWith("done"), waitMs(30000));
    QCOMPARE(eta->text(), QString("done: %1 views written, %2 were already there").arg(6 - before).arg(before));
    QCOMPARE(dataset::Dataset::readManifest(dataset.toStdString()).size(), std::size_t(6));
    QVERIFY(dataset::Dataset::verify(dataset.toStdString()).ok());
  }

  void aPulledCableShowsTheBannerAndTheSessionRecovers() {
    ObservedFactory observed(*factory_);
    StudioWindow w(observed, simulated("ycb_025_mug"));
    w.show();
    QTRY_VERIFY_WITH_TIMEOUT(w.rates().frames > 10, waitMs(15000));
    auto* unplug = w.findChild<QCheckBox*>("simUnplug");
    QVERIFY(unplug);
    unplug->setChecked(true);
    QTRY_VERIFY_WITH_TIMEOUT(!w.bannerText().isEmpty(), waitMs(15000));
    QVERIFY2(w.bannerText().startsWith("Camera stopped answering: "), qPrintable(w.bannerText()));
    QVERIFY2(w.bannerText().contains("SR4000"), qPrintable(w.bannerText()));  // names the device
    const long frames_while_out = w.rates().frames;
    // Nothing arrives while unplugged: not after two attempts to open it again have failed.
    const long opens = observed.opens;
    QTRY_VERIFY_WITH_TIMEOUT(observed.opens >= opens + 2, waitMs(10000));
    QCoreApplication::processEvents();
    QCOMPARE(w.rates().frames, frames_while_out);
    QVERIFY2(!w.bannerText().isEmpty(), "the banner stays while the camera is out");
    unplug->setChecked(false);
    const long results_while_out = w.rates().results;
    QTRY_VERIFY_WITH_TIMEOUT(w.bannerText().isEmpty(), waitMs(15000));
    QTRY_VERIFY_WITH_TIMEOUT(w.rates().frames > frames_while_out + 10, waitMs(15000));
    // The reopened camera counts its frames from 0 again: recognition must follow it.
    QTRY_VERIFY_WITH_TIMEOUT(w.rates().results > results_while_out + 10, waitMs(15000));
  }

  // --object with --camera (the simulated OpenNI2 camera's default device looks at the studio's
  // object): the object asked for, not the one the settings kept from the last run (the scissors,
  // which the OpenNI2 screenshot of the docs once showed instead of the mug).
  void theObjectAskedForWinsOverTheOneUsedLast() {
    {
      StudioWindow last(*factory_, simulated("ycb_037_scissors"));
      last.show();
      QTRY_VERIFY_WITH_TIMEOUT(last.rates().frames > 0, waitMs(15000));
      last.close();  // saves the settings, the object among them
    }
    ::setenv("KEYTURN_MESASR_LIB", "/nonexistent/libmesasr.so", 1);  // the camera need not open
    StudioOptions o;
    o.settings_file = file("studio.ini").toStdString();
    o.camera = rig::CameraSpec::parse("eth:192.0.2.7");
    o.sim_object = "ycb_025_mug";
    StudioWindow w(*factory_, o);
    w.show();
    QCOMPARE(w.findChild<QComboBox*>("simObject")->currentData().toString(), QString("ycb_025_mug"));
    QTRY_VERIFY_WITH_TIMEOUT(!w.bannerText().isEmpty(), waitMs(10000));
    ::unsetenv("KEYTURN_MESASR_LIB");
  }

  void aCameraThatCannotBeOpenedIsNamedInTheBanner() {
    StudioOptions o;
    o.settings_file = file("eth.ini").toStdString();
    StudioWindow w(*factory_, o);
    w.show();
    w.findChild<QComboBox*>("cameraKind")->setCurrentIndex(2);  // Ethernet
    w.findChild<QLineEdit*>("cameraAddress")->setText("192.0.2.7");
    ::setenv("KEYTURN_MESASR_LIB", "/nonexistent/libmesasr.so", 1);  // no MESA library here
    QTest::mouseClick(w.findChild<QPushButton*>("cameraConnect"), Qt::LeftButton);
    QTRY_VERIFY_WITH_TIMEOUT(!w.bannerText().isEmpty(), waitMs(10000));
    ::unsetenv("KEYTURN_MESASR_LIB");
    QVERIFY2(w.bannerText().startsWith("Could not open the camera: SR4000 at 192.0.2.7: "), qPrintable(w.bannerText()));
    QVERIFY2(w.bannerText().contains("libMesaSR"), qPrintable(w.bannerText()));
    QCOMPARE(w.findChild<QPushButton*>("cameraConnect")->text(), QString("Connect"));
    // The Devices panel's status shows the whole message, a long path wrapped, none of it cut off
    // (issue 52: an OpenNI2 error was cut after "/lib/x86_64-linux-gnu/"), and holds it as its tooltip.
    auto* status = w.findChild<QLabel*>("cameraStatus");
    const QString message = w.bannerText().mid(QString("Could not open the camera: ").size());
    QCOMPARE(status->toolTip(), message);
    // The layout settles over more than one pass of the event loop on a loaded machine: wait for it.
    QTRY_VERIFY2_WITH_TIMEOUT(status->height() >= status->heightForWidth(status->width()),
                              qPrintable(QString("%1 px tall, its text needs %2")
                                             .arg(status->height())
                                             .arg(status->heightForWidth(status->width()))),
                              waitMs(5000));
  }

  void theUsbListFollowsCamerasPluggedInAndOut() {
    ObservedFactory usb(*factory_);
    StudioOptions o;
    o.settings_file = file("usb.ini").toStdString();
    StudioWindow w(usb, o);
    w.show();
    auto* list = w.findChild<QComboBox*>("usbCameras");
    QVERIFY(list);
    w.findChild<QComboBox*>("cameraKind")->setCurrentIndex(1);  // USB
    QCOMPARE(list->count(), 1);
    QCOMPARE(list->itemText(0), QString("no SwissRanger on USB"));
    const int scans_before = usb.scans;
    const int polls = usb.polls;
    QTRY_VERIFY_WITH_TIMEOUT(usb.polls >= polls + 2, waitMs(5000));
    QCOMPARE(usb.scans, scans_before);  // the bus polled twice, no change on it: no rescan
    // Each listed camera opens as the spec rig made of what USB found (rig/found_camera.h).
    auto sr4000 = [](const std::string& serial, const std::string& port) {
      drivers::UsbCameraInfo c;
      c.model = "SR4000";
      c.serial = serial;
      c.port_path = port;
      c.accessible = true;
      return rig::foundCamera(c);
    };
    auto* kind = w.findChild<QComboBox*>("cameraKind");
    usb.plug({sr4000("4000123", "1-2"), sr4000("4000456", "3-1")});
    QTRY_COMPARE_WITH_TIMEOUT(list->count(), 2, waitMs(3000));
    QCOMPARE(list->itemText(0), QString("SR4000 4000123 on USB 1-2"));
    list->setCurrentIndex(1);
    QCOMPARE(kind->currentIndex(), 1);
    QCOMPARE(QString::fromStdString(w.findChild<DevicesPanel*>()->cameraSpec().toString()), QString("usb:4000456"));
    usb.plug({sr4000("4000456", "3-1")});  // the first one pulled out
    QTRY_COMPARE_WITH_TIMEOUT(list->count(), 1, waitMs(3000));
    QCOMPARE(QString::fromStdString(w.findChild<DevicesPanel*>()->cameraSpec().toString()), QString("usb:4000456"));
    usb.plug({});
    QTRY_COMPARE_WITH_TIMEOUT(list->itemText(0), QString("no SwissRanger on USB"), waitMs(3000));
  }

  void playsBackARecordingWithLiveRecognition() {
    ObservedFactory observed(*factory_);
    StudioWindow w(observed, playback(25));
    w.show();
    QTRY_COMPARE_WITH_TIMEOUT(w.recognisedClass(), QString("ycb_035_power_drill"), waitMs(20000));
    // Live, frames are dropped as the machine's load decides, so the agreement here is not asserted:
    // recognisesEveryRecordedViewAsTheModelDoes feeds every frame and asserts it.
    QVERIFY2(w.bannerText().isEmpty(), qPrintable(w.bannerText()));
    // More frames than the recording holds: it loops.
    QTRY_VERIFY_WITH_TIMEOUT(observed.acquired > 12, waitMs(10000));
    auto* status = w.findChild<QLabel*>("cameraStatus");
    QVERIFY2(status->text().contains("recording " + recording_ + " (12 views, 25 frames/s, looping)"), qPrintable(status->text()));
    // The pose shown is one the recording holds (its measured angles, near every 30°).
    auto* angle = w.findChild<QLabel*>("poseAngle");
    QTRY_VERIFY_WITH_TIMEOUT(angle->text().endsWith("°"), waitMs(5000));
    // It follows the frames: several recorded angles go by, each near a multiple of 30°.
    QSet<QString> angles;
    const auto seen = [&] {
      angles.insert(angle->text());
      return angles.size() >= 4;
    };
    QTRY_VERIFY_WITH_TIMEOUT(seen(), waitMs(10000));
    for (const QString& a : angles) {
      const double deg = QString(a).chopped(1).toDouble();
      QVERIFY2(std::abs(deg - 30.0 * std::round(deg / 30.0)) < 0.2, qPrintable(a));
    }
    // Move to seeks the recording and holds there: the pose and the frames stay at 90°.
    w.findChild<QDoubleSpinBox*>("poseTarget")->setValue(90);
    QTest::mouseClick(w.findChild<QPushButton*>("poseMoveTo"), Qt::LeftButton);
    QTRY_VERIFY_WITH_TIMEOUT(std::abs(angle->text().chopped(1).toDouble() - 90) < 0.2, waitMs(5000));
    const long acquired = observed.acquired;
    QTRY_VERIFY_WITH_TIMEOUT(framesDelivered(observed, acquired, 15), waitMs(10000));
    QVERIFY2(std::abs(angle->text().chopped(1).toDouble() - 90) < 0.2, qPrintable(angle->text()));
  }

  // Issue 51: the agreement of live playback depended on which frames a loaded machine dropped (a bar
  // loosened 0.8 -> 0.7 -> > 0.5). Here the camera takes the next frame only after the last one's
  // result arrived, so the studio recognises every view in order, and its answers and agreement are
  // the model's own per-view answers, computed here by the recogniser outside the studio.
  void recognisesEveryRecordedViewAsTheModelDoes() {
    const std::string model = std::string(KEYTURN_DATA_DIR) + "/models/sim-objects";
    const learning::Recognizer recognizer = learning::Recognizer::load(model);
    const auto& classes = recognizer.info().classes;
    rig::Recording recording(recording_.toStdString(), {1000, true});
    std::vector<QString> answers;  // per recorded view, as the studio names a stable class
    for (std::size_t v = 0; v < recording.views().size(); ++v) {
      const learning::Recognition r = recognizer.recognize(recording.next().cloud);
      answers.push_back(r.answer == learning::Answer::Unknown ? QString("unknown")
                                                              : QString::fromStdString(classes.at(static_cast<std::size_t>(r.best))));
    }
    QCOMPARE(answers.size(), std::size_t(12));
    const auto drill = static_cast<int>(std::count(answers.begin(), answers.end(), QString("ycb_035_power_drill")));
    // `keyturn classify` on this recording: 11 of 12 views are the drill (the built-in model made with
    // the filled keypoint budget, 2026-12-07; 10 with the one before).
    QVERIFY2(drill == 11, qPrintable(QString("%1 of 12 views the drill").arg(drill)));

    ObservedFactory observed(*factory_);
    observed.gate.allow(1);
    StudioWindow w(observed, playback(25));
    const auto open = qScopeGuard([&] { observed.gate.open(); });  // before the window closes its camera
    w.show();
    // 32 frames, one at a time: the last 20 results are views 0-11 and 0-7 (the view not the drill once or twice).
    const long frames = 32;
    for (long n = 1; n <= frames; ++n) {
      QTRY_VERIFY2_WITH_TIMEOUT(w.rates().results == n, qPrintable(QString("frame %1: %2 results").arg(n).arg(w.rates().results)),
                                waitMs(20000));
      if (n < frames) observed.gate.allow(n + 1);
    }
    QCOMPARE(w.rates().dropped, 0L);
    QCOMPARE(w.rates().frames, frames);
    std::map<QString, int> last20;
    for (long n = frames - 20; n < frames; ++n) ++last20[answers[static_cast<std::size_t>(n % 12)]];
    const auto mode = std::max_element(last20.begin(), last20.end(), [](auto& a, auto& b) { return a.second < b.second; });
    QCOMPARE(w.recognisedClass(), mode->first);
    QCOMPARE(w.recognisedAgreement(), mode->second / 20.0);
    QVERIFY2(w.recognisedAgreement() >= 0.8, qPrintable(QString::number(w.recognisedAgreement())));  // 18 or 19 of 20
  }

  void aRecordingPlayedOnceEndsAfterItsViewsWithoutABanner() {
    ObservedFactory observed(*factory_);
    StudioOptions o = playback(50);
    o.playback.loop = false;
    StudioWindow w(observed, o);
    w.show();
    auto* status = w.findChild<QLabel*>("cameraStatus");
    QTRY_VERIFY_WITH_TIMEOUT(status->text().contains("end of the recording after its 12 views (not looping)"), waitMs(15000));
    QCoreApplication::processEvents();
    QCOMPARE(w.rates().frames, 12L);   // every view once, none twice
    QCOMPARE(observed.opens.load(), 1L);  // the end is not a camera lost: no reconnecting
    QVERIFY2(w.bannerText().isEmpty(), qPrintable(w.bannerText()));
    // Connect again: it plays from the first view.
    auto* connect = w.findChild<QPushButton*>("cameraConnect");
    QTest::mouseClick(connect, Qt::LeftButton);  // disconnect
    QTRY_COMPARE_WITH_TIMEOUT(connect->text(), QString("Connect"), waitMs(5000));
    QTest::mouseClick(connect, Qt::LeftButton);
    QTRY_VERIFY_WITH_TIMEOUT(status->text().contains("end of the recording"), waitMs(15000));
    QCoreApplication::processEvents();
    QCOMPARE(w.rates().frames, 24L);
  }

  void settingsPersistAcrossSessions() {
    const std::string ini = file("persist.ini").toStdString();
    {
      StudioOptions o;
      o.settings_file = ini;
      StudioWindow w(*factory_, o);
      w.findChild<QDoubleSpinBox*>("captureStep")->setValue(7.5);
      w.findChild<QLineEdit*>("captureFolder")->setText("/data/rig-a");
      w.close();
    }
    StudioOptions o;
    o.settings_file = ini;
    StudioWindow w(*factory_, o);
    QCOMPARE(w.findChild<QDoubleSpinBox*>("captureStep")->value(), 7.5);
    QCOMPARE(w.findChild<QLineEdit*>("captureFolder")->text(), QString("/data/rig-a"));
  }

  // The whole window, status bar included, fits a 1600 × 1000 screen with a title bar (it was
  // 1,025 px tall: the Devices and Recognition panels set the minimum height).
  void theWindowFitsA1600By1000Screen() {
    StudioWindow w(*factory_, simulated("ycb_025_mug"));
    w.show();
    QVERIFY(QTest::qWaitForWindowExposed(&w));
    QVERIFY2(w.minimumSizeHint().height() <= 960, qPrintable(QString::number(w.minimumSizeHint().height())));
    QVERIFY2(w.height() <= 960 && w.width() <= 1600, qPrintable(QString("%1 x %2").arg(w.width()).arg(w.height())));
    auto* rates = w.findChild<QLabel*>("rates");
    QVERIFY(rates);
    QVERIFY(rates->isVisible());
    QVERIFY(rates->mapTo(&w, QPoint(0, rates->height())).y() <= w.height());
  }

  // At 1600 × 960 every turntable control is in view without scrolling the Devices panel (under the
  // capture dock it was not: jog, Home, Move to and Stop sat below the fold).
  void theTurntableControlsAreInViewAt1600By960() {
    StudioWindow w(*factory_, simulated("ycb_025_mug"));
    w.resize(1600, 960);
    w.show();
    QVERIFY(QTest::qWaitForWindowExposed(&w));
    auto* move_to = w.findChild<QPushButton*>("poseMoveTo");
    QVERIFY(move_to);
    QScrollArea* area = nullptr;
    for (QWidget* p = move_to->parentWidget(); p && !area; p = p->parentWidget()) area = qobject_cast<QScrollArea*>(p);
    QVERIFY(area);
    QCOMPARE(area->verticalScrollBar()->value(), 0);
    const int bottom = move_to->mapTo(area->viewport(), QPoint(0, move_to->height())).y();
    QVERIFY2(bottom <= area->viewport()->height(),
             qPrintable(QString("Move to ends at %1 px, the Devices panel shows %2").arg(bottom).arg(area->viewport()->height())));
  }
};

QTEST_MAIN(StudioTest)
#include "studio_test.moc"
