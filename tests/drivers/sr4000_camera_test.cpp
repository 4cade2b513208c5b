// The real SR4000 driver against libmesasr-sim, loaded exactly as MESA's
// library would be.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <vector>

#include "keyturn/core/error.h"
#include "support/error_of.h"
#include "keyturn/drivers/sr4000_camera.h"
#include "keyturn/sim/mesasr_sim_config.h"
#include "keyturn/sim/tof_view.h"
#include "support/scratch_path.h"

namespace fs = std::filesystem;
using namespace keyturn;
using keyturn::test::errorOf;
using namespace keyturn::drivers;

namespace {

class Sr4000SimTest : public ::testing::Test {
 protected:
  void SetUp() override {
    useConfig(sim::MesaSrSimConfig());
    lib_ = MesaSrLibrary::load(KEYTURN_MESASR_SIM_PATH);
  }
  void TearDown() override { ::unsetenv("MESASR_SIM_CONFIG"); }

  void useConfig(const sim::MesaSrSimConfig& c) {
    const std::string path = (dir_ / "sim.json").string();
    c.save(path);
    ::setenv("MESASR_SIM_CONFIG", path.c_str(), 1);
  }

  std::unique_ptr<Sr4000Camera> open(const std::string& how = "usb") {
    Sr4000Options o;
    o.backoff_initial_ms = 1;
    o.log = [this](const std::string& line) { log_.push_back(line); };
    return std::make_unique<Sr4000Camera>(lib_, Sr4000Connection::parse(how), o);
  }

  const keyturn::test::ScratchFolder scratch_{"sr4000"};
  const fs::path& dir_ = scratch_.made();
  std::shared_ptr<MesaSrLibrary> lib_;
  std::vector<std::string> log_;
};


}  // namespace

TEST(MesaSrLibrary, MissingLibraryIsOneClearLine) {
  const std::string msg = errorOf([] { MesaSrLibrary::load("/nonexistent/libmesasr.so"); });
  EXPECT_NE(msg.find("libMesaSR not found (tried /nonexistent/libmesasr.so"), std::string::npos) << msg;
  EXPECT_EQ(msg.find('\n'), std::string::npos);
}

TEST(MesaSrLibrary, WrongLibraryIsNamed) {
  const std::string msg = errorOf([] { MesaSrLibrary::load("libm.so.6"); });
  EXPECT_NE(msg.find("libm.so.6: not a usable libMesaSR (missing SR_OpenUSB"), std::string::npos) << msg;
}

TEST(MesaSrSimConfig, IntegersThatDoNotFitAreNamedNotCast) {
  const keyturn::test::ScratchFolder scratch("simcfg");
  const auto path = (scratch.made() / "sim.json").string();
  auto err = [&](const std::string& json) {
    std::ofstream(path) << json;
    return errorOf([&] { sim::MesaSrSimConfig::fromFile(path); });
  };
  EXPECT_EQ(err(R"({"serial": 1e30})"), path + ": serial must be an integer in 0..4294967295, not 1e+30");
  EXPECT_EQ(err(R"({"seed": -1})"), path + ": seed must be an integer in 0..18446744073709551615, not -1");
  EXPECT_EQ(err(R"({"faults": {"timeout_every": 2.5}})"),
            path + ": faults: timeout_every must be an integer in 0..2147483647, not 2.5");
  std::ofstream(path) << R"({"serial": 4294967295, "seed": 18446744073709551615, "faults": {"disconnect_after": 7}})";
  const auto c = sim::MesaSrSimConfig::fromFile(path);
  EXPECT_EQ(c.serial, 4294967295u);
  EXPECT_EQ(c.seed, 18446744073709551615ull);  // exact: read as an unsigned integer, not through double
  EXPECT_EQ(c.faults.disconnect_after, 7);
  EXPECT_EQ(err(R"({"roll": 120})"), path + ": roll must be within ±90°");
  EXPECT_EQ(err(R"({"scale": 0})"), path + ": scale must be in [0.1, 10]");
  sim::MesaSrSimConfig rolled;
  rolled.roll = -2.5;
  rolled.scale = 1.25;
  rolled.save(path);
  EXPECT_EQ(sim::MesaSrSimConfig::fromFile(path).roll, -2.5);
  EXPECT_EQ(sim::MesaSrSimConfig::fromFile(path).scale, 1.25);
  fs::remove(path);
}

TEST(Sr4000Connection, ParsesUsbAndEthernet) {
  EXPECT_EQ(Sr4000Connection::parse("usb").serial, 0u);
  EXPECT_EQ(Sr4000Connection::parse("usb:4000123").serial, 4000123u);
  EXPECT_EQ(Sr4000Connection::parse("eth:192.168.1.42").address, "192.168.1.42");
  EXPECT_THROW(Sr4000Connection::parse("eth:camera"), Error);
  EXPECT_THROW(Sr4000Connection::parse("usb:abc"), Error);
  EXPECT_THROW(Sr4000Connection::parse("firewire"), Error);
}

TEST_F(Sr4000SimTest, OpensByUsbSerialAndEthernet) {
  auto usb = open("usb");
  EXPECT_EQ(usb->serial(), 4000123u);
  EXPECT_NE(usb->deviceString().find("VendorID:0x1ad2, ProductID:0x0075"), std::string::npos);
  EXPECT_EQ(usb->firmwareVersion(), 0x57);
  auto by_serial = open("usb:4000123");
  EXPECT_EQ(by_serial->serial(), 4000123u);
  auto eth = open("eth:10.0.0.7");
  EXPECT_NE(eth->deviceString().find("SR4000-ETH"), std::string::npos);
  const std::string msg = errorOf([&] { open("usb:42"); });
  EXPECT_NE(msg.find("SR4000 USB serial 42"), std::string::npos) << msg;
  EXPECT_NE(msg.find("could not open the camera (open returned 0)"), std::string::npos) << msg;
}

TEST_F(Sr4000SimTest, EveryParameterReadsBack) {
  auto cam = open();
  TofSettings s;
  s.integration_time = 77;
  s.modulation_frequency = MF_15MHz;
  s.amplitude_threshold = 123;
  s.distance_offset = 45;
  s.acquire_mode = AM_COR_FIX_PTRN | AM_MEDIAN;
  s.auto_exposure.enabled = false;
  cam->configure(s);
  const TofSettings r = cam->settings();
  EXPECT_EQ(r.integration_time, 77);
  EXPECT_EQ(r.modulation_frequency, MF_15MHz);
  EXPECT_EQ(r.amplitude_threshold, 123);
  EXPECT_EQ(r.distance_offset, 45);
  EXPECT_EQ(r.acquire_mode, static_cast<std::uint32_t>(AM_COR_FIX_PTRN | AM_MEDIAN));
}

TEST_F(Sr4000SimTest, XyzAgreesWithDistanceAndIntrinsics) {
  auto cam = open();
  const TofFrame f = cam->acquire();
  ASSERT_EQ(f.width, 176u);
  ASSERT_EQ(f.height, 144u);
  ASSERT_EQ(f.confidence.size(), 176u * 144u);  // default mode includes the confidence map
  const sim::Intrinsics k;
  const double range = nonAmbiguousRange(MF_30MHz);
  EXPECT_NEAR(range, 4.9965, 1e-3);
  std::size_t valid = 0;
  for (std::size_t i = 0; i < f.distance.size(); ++i) {
    const auto& p = f.cloud.points[i];
    if (f.distance[i] == 0) {
      EXPECT_FALSE(Cloud::isValid(p));
      continue;
    }
    ++valid;
    EXPECT_NEAR(p.norm(), f.distance[i] / 65535.0 * range, 1e-4);
    EXPECT_NEAR(k.fx * p.x() / p.z() + k.cx - 0.5, static_cast<double>(i % 176), 1e-2);
    EXPECT_NEAR(k.fy * p.y() / p.z() + k.cy - 0.5, static_cast<double>(i / 176), 1e-2);
  }
  EXPECT_GT(valid, 20000u);
}

// Like a real SR4000's, the confidence map is graded (it was 0 or 65535): higher amplitude, higher confidence.
TEST_F(Sr4000SimTest, ConfidenceMapIsGraded) {
  auto cam = open();
  const TofFrame f = cam->acquire();
  ASSERT_EQ(f.confidence.size(), f.amplitude.size());
  std::vector<std::pair<std::uint16_t, std::uint16_t>> amp_conf;
  std::size_t full = 0;
  for (std::size_t i = 0; i < f.distance.size(); ++i) {
    if (f.distance[i] == 0) {
      EXPECT_EQ(f.confidence[i], 0) << i;
      continue;
    }
    if (f.confidence[i] == 65535) ++full;
    amp_conf.emplace_back(f.amplitude[i], f.confidence[i]);
  }
  ASSERT_GT(amp_conf.size(), 20000u);
  EXPECT_EQ(full, 0u);
  std::sort(amp_conf.begin(), amp_conf.end());
  std::vector<std::uint16_t> levels;
  for (const auto& ac : amp_conf) levels.push_back(static_cast<std::uint16_t>(ac.second / 1000));
  std::sort(levels.begin(), levels.end());
  EXPECT_GT(std::unique(levels.begin(), levels.end()) - levels.begin(), 20);
  // Median confidence of the weakest tenth of the returns is below that of the strongest tenth.
  const std::size_t tenth = amp_conf.size() / 10;
  std::vector<std::uint16_t> weak, strong;
  for (std::size_t i = 0; i < tenth; ++i) {
    weak.push_back(amp_conf[i].second);
    strong.push_back(amp_conf[amp_conf.size() - 1 - i].second);
  }
  std::nth_element(weak.begin(), weak.begin() + tenth / 2, weak.end());
  std::nth_element(strong.begin(), strong.begin() + tenth / 2, strong.end());
  EXPECT_LT(weak[tenth / 2] + 10000, strong[tenth / 2]);
}

TEST_F(Sr4000SimTest, AmplitudeThresholdZeroesWeakPixels) {
  auto cam = open();
  TofSettings s;
  s.amplitude_threshold = 6000;
  cam->configure(s);
  const TofFrame f = cam->acquire();
  std::size_t zeroed = 0, kept = 0;
  for (std::size_t i = 0; i < f.distance.size(); ++i) {
    if (f.amplitude[i] < 6000) {
      EXPECT_EQ(f.distance[i], 0) << i;
      ++zeroed;
    } else if (f.distance[i] != 0) {
      ++kept;
    }
  }
  EXPECT_GT(zeroed, 1000u);
  EXPECT_GT(kept, 1000u);
}

TEST_F(Sr4000SimTest, ImageListIsReallocatedBySetModeAndTheDriverFollows) {
  SRCAM cam = nullptr;
  ASSERT_EQ(lib_->SR_OpenUSB(&cam, 0), 1);
  ImgEntry* before = nullptr;
  // Opened in libMesaSR's SR4000 mode: no confidence map.
  ASSERT_EQ(lib_->SR_GetMode(cam), AM_COR_FIX_PTRN | AM_CONV_GRAY | AM_DENOISE_ANF);
  ASSERT_EQ(lib_->SR_GetImageList(cam, &before), 2);
  void* old_distance = before[0].data;
  ASSERT_EQ(lib_->SR_SetMode(cam, AM_COR_FIX_PTRN | AM_CONF_MAP), 0);
  ImgEntry* after = nullptr;
  EXPECT_EQ(lib_->SR_GetImageList(cam, &after), 3);
  EXPECT_EQ(after[2].imgType, IT_CONF_MAP);
  EXPECT_NE(after[0].data, old_distance);
  ASSERT_EQ(lib_->SR_SetMode(cam, AM_COR_FIX_PTRN), 0);
  EXPECT_EQ(lib_->SR_GetImageList(cam, &after), 2);  // no confidence map without AM_CONF_MAP
  lib_->SR_Close(cam);

  auto drv = open();
  TofSettings s;
  s.acquire_mode = AM_COR_FIX_PTRN | AM_CONV_GRAY;
  drv->configure(s);
  const TofFrame f = drv->acquire();
  EXPECT_TRUE(f.confidence.empty());
  EXPECT_GT(f.cloud.validCount(), 20000u);
}

TEST_F(Sr4000SimTest, CallbackSeesModeChanges) {
  static std::vector<unsigned> messages;
  messages.clear();
  SR_FuncCB* old = lib_->SR_SetCallback([](SRCAM, unsigned msg, unsigned, void*) {
    messages.push_back(msg);
    return 0;
  });
  EXPECT_EQ(old, lib_->SR_GetDefaultCallback());
  open();
  lib_->SR_SetCallback(old);
  EXPECT_NE(std::find(messages.begin(), messages.end(), static_cast<unsigned>(CM_PROGRESS)), messages.end());
  EXPECT_NE(std::find(messages.begin(), messages.end(), static_cast<unsigned>(CM_CHANGING)), messages.end());
  EXPECT_NE(std::find(messages.begin(), messages.end(), static_cast<unsigned>(CM_CHANGED)), messages.end());
}

TEST_F(Sr4000SimTest, PhaseWrapsBeyondTheNonAmbiguousRange) {
  sim::MesaSrSimConfig c;
  c.distance = 3.0;
  useConfig(c);
  auto cam = open();
  TofSettings s;
  s.modulation_frequency = MF_60MHz;  // 2.498 m non-ambiguous range
  cam->configure(s);
  const TofFrame f = cam->acquire();
  const auto& p = f.cloud.points[72 * 176 + 88];
  ASSERT_TRUE(Cloud::isValid(p));
  // The mug's front wall is ~4 cm nearer than its centre at 3 m.
  EXPECT_NEAR(p.norm(), 3.0 - 0.04 - nonAmbiguousRange(MF_60MHz), 0.02);
}

// noise_per_pose: one noise draw per turntable angle, so a still table gives equal frames (the studio's
// deterministic recognition test); without it every frame draws its own, as a sensor's.
TEST_F(Sr4000SimTest, NoisePerPoseGivesEqualFramesAtOnePoseAndANewDrawAtAnother) {
  auto frames = [&](bool per_pose, double angle) {
    sim::MesaSrSimConfig c;
    c.noise_per_pose = per_pose;
    c.turntable_deg = angle;
    useConfig(c);
    auto cam = open();
    const TofFrame a = cam->acquire(), b = cam->acquire();
    return std::make_pair(a.distance, b.distance);
  };
  const auto still = frames(true, 0.0);
  EXPECT_EQ(still.first, still.second);
  const auto turned = frames(true, 5.0);
  EXPECT_NE(turned.first, still.first);
  EXPECT_EQ(frames(true, 0.0).first, still.first) << "the same draw at the same angle, camera after camera";
  const auto per_frame = frames(false, 0.0);
  EXPECT_NE(per_frame.first, per_frame.second);
}

TEST_F(Sr4000SimTest, TimeoutsAreRetriedByReopening) {
  sim::MesaSrSimConfig c;
  c.faults.timeout_every = 2;
  useConfig(c);
  auto cam = open();
  for (int i = 0; i < 4; ++i) EXPECT_GT(cam->acquire().cloud.validCount(), 20000u);
  EXPECT_GE(cam->reconnects(), 1);
  ASSERT_FALSE(log_.empty());
  EXPECT_NE(log_[0].find("SR_Acquire failed (-1); reopening in 1 ms (attempt 1 of 3)"), std::string::npos)
      << log_[0];
}

TEST_F(Sr4000SimTest, DisconnectIsRecoveredByReopening) {
  sim::MesaSrSimConfig c;
  c.faults.disconnect_after = 2;
  useConfig(c);
  auto cam = open();
  cam->acquire();
  cam->acquire();
  const TofFrame third = cam->acquire();  // the camera went silent: closed, reopened, acquired
  EXPECT_EQ(cam->reconnects(), 1);
  EXPECT_GT(third.cloud.validCount(), 20000u);
}

TEST_F(Sr4000SimTest, PersistentlyCorruptFramesEndInAClearError) {
  sim::MesaSrSimConfig c;
  c.faults.corrupt_every = 1;
  useConfig(c);
  auto cam = open();
  const std::string msg = errorOf([&] { cam->acquire(); });
  EXPECT_NE(msg.find("giving up after 3 reopen attempts: corrupt frame: 33792 bytes transferred, expected 101376"),
            std::string::npos)
      << msg;
  EXPECT_EQ(log_.size(), 3u);
}

TEST_F(Sr4000SimTest, OpenFailureIsAClearError) {
  sim::MesaSrSimConfig c;
  c.faults.open_fail = true;
  useConfig(c);
  const std::string msg = errorOf([&] { open("eth:10.0.0.9"); });
  EXPECT_NE(msg.find("SR4000 at 10.0.0.9"), std::string::npos) << msg;
  EXPECT_NE(msg.find("open returned -1"), std::string::npos) << msg;
}

TEST_F(Sr4000SimTest, CameraSeesTheTurntableAngleOfTheSharedWorld) {
  sim::MesaSrSimConfig c;
  c.world = (dir_ / "world.json").string();
  useConfig(c);
  sim::writeWorldTurntable(c.world, 0.0);
  auto cam = open();
  const TofFrame a = cam->acquire();
  sim::writeWorldTurntable(c.world, 90.0);
  const TofFrame b = cam->acquire();
  // The mug's handle moves: many pixels change by more than noise.
  std::size_t changed = 0;
  for (std::size_t i = 0; i < a.distance.size(); ++i)
    if (std::abs(static_cast<int>(a.distance[i]) - static_cast<int>(b.distance[i])) > 200) ++changed;
  EXPECT_GT(changed, 100u);
}

TEST_F(Sr4000SimTest, ShorterIntegrationTimeIsNoisier) {
  auto cam = open();
  auto spread = [&](int it) {
    TofSettings s;
    s.integration_time = static_cast<std::uint8_t>(it);
    s.auto_exposure.enabled = false;
    cam->configure(s);
    std::vector<double> d;
    for (int i = 0; i < 15; ++i) d.push_back(cam->acquire().cloud.points[72 * 176 + 88].norm());
    double mean = 0, var = 0;
    for (double x : d) mean += x / d.size();
    for (double x : d) var += (x - mean) * (x - mean) / d.size();
    return std::sqrt(var);
  };
  const double short_it = spread(3), long_it = spread(200);
  EXPECT_GT(short_it, 2.0 * long_it);  // σ ∝ 1/sqrt(0.3 ms + n·0.1 ms): 0.6 ms vs 20.3 ms
}

TEST_F(Sr4000SimTest, SaturatedPixelsHaveNoConfidence) {
  sim::MesaSrSimConfig c;
  c.distance = 0.25;  // very close, with the longest integration time
  useConfig(c);
  auto cam = open();
  TofSettings s;
  s.integration_time = 255;
  s.auto_exposure.enabled = false;
  cam->configure(s);
  const TofFrame f = cam->acquire();
  std::size_t saturated = 0;
  for (std::size_t i = 0; i < f.amplitude.size(); ++i)
    if (f.amplitude[i] == 65535 && f.distance[i] != 0) {
      ++saturated;
      EXPECT_EQ(f.confidence[i], 0) << i;
    }
  EXPECT_GT(saturated, 500u);
  // At the default integration time and distance nothing saturates.
  useConfig(sim::MesaSrSimConfig());
  auto normal = open();
  const TofFrame g = normal->acquire();
  EXPECT_EQ(std::count(g.amplitude.begin(), g.amplitude.end(), 65535), 0);
}

TEST_F(Sr4000SimTest, AFrameRateSpacesTheFramesLikeARealCamera) {
  sim::MesaSrSimConfig c;
  c.frame_rate = 25;
  useConfig(c);
  auto cam = open();
  // The first frame is due at once, each later one a period after the one before: seven frames
  // take at least six periods from before the first call (a lower bound with no slack to lose on a
  // loaded machine, which can only make them later). Unpaced, seven frames render in ~25 ms.
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < 7; ++i) cam->acquire();
  EXPECT_GE(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 6 * 0.040);
}

TEST_F(Sr4000SimTest, AnUnpluggedCameraFailsUntilPluggedBackIn) {
  sim::MesaSrSimConfig c;
  c.unplug_file = (dir_ / "unplugged").string();
  useConfig(c);
  auto cam = open();
  EXPECT_EQ(cam->acquire().width, 176u);
  std::ofstream(c.unplug_file) << "";
  const std::string msg = errorOf([&] { cam->acquire(); });
  EXPECT_NE(msg.find("SR4000"), std::string::npos) << msg;  // names the device
  EXPECT_THROW(open(), Error);                              // and it cannot be opened either
  fs::remove(c.unplug_file);
  EXPECT_EQ(open()->acquire().width, 176u);
}
