#pragma once
// A Time-of-Flight camera as keyturn uses it: configure, acquire frames of
// distance, amplitude and confidence with XYZ in metres.
#include <chrono>
#include <optional>
#include <cstdint>
#include <string>
#include <vector>

#include "keyturn/core/cloud.h"
#include "keyturn/core/depth_image.h"
#include "keyturn/core/error.h"

namespace keyturn::drivers {

// MESA's SR4000 recommendation is COR_FIX_PTRN | CONV_GRAY | DENOISE_ANF; the
// confidence map is added so every frame carries one (as the ROS driver does).
constexpr std::uint32_t kSr4000DefaultMode = 0x01 | 0x10 | 0x800 | 0x100;

struct AutoExposure {
  bool enabled = true;
  std::uint8_t min_int_time = 1;  // MESA's SR4000 recommendation 1, 150, 5, 70
  std::uint8_t max_int_time = 150;
  std::uint8_t percent_over_pos = 5;
  std::uint8_t desired_pos = 70;
};

struct TofSettings {
  std::uint8_t integration_time = 30;  // SR4000: 0.3 ms + n × 0.1 ms
  AutoExposure auto_exposure;
  int modulation_frequency = 1;        // ModulationFrq index; 1 = 30 MHz (5.0 m range)
  std::uint16_t amplitude_threshold = 0;
  std::uint16_t distance_offset = 0;
  std::uint32_t acquire_mode = kSr4000DefaultMode;
  int timeout_ms = 3000;
};

// Non-ambiguous range c / (2 f) in metres for a ModulationFrq index; 0 if unknown.
double nonAmbiguousRange(int modulation_frequency);
double modulationMHz(int modulation_frequency);
// The SR4000 frequency index of mhz; throws keyturn::Error naming --modulation and the choices.
int modulationIndex(double mhz);

// What a structured-light depth camera (OpenNI2: Kinect, Xtion, Astra) adds to a frame. Its `distance`
// is then the depth image (z along the optical axis, in depth_unit_m per unit; 0 = no return), its
// `amplitude` the IR image when one was streamed, and `confidence` stays empty.
struct DepthCameraFrame {
  double depth_unit_m = 0.001;             // metres per depth unit (OpenNI2's 1 mm or 100 µm formats)
  DepthIntrinsics intrinsics;              // the pinhole the cloud was made with
  std::uint64_t device_timestamp_us = 0;   // the device's own clock (OpenNI2: µs since the stream started)
  std::uint32_t colour_width = 0, colour_height = 0;
  std::vector<std::uint8_t> colour;        // RGB888 row-major; empty without a colour stream
  bool registered = false;                 // depth was registered to the colour image by the device
};

struct TofFrame {
  std::uint32_t width = 0, height = 0;
  std::vector<std::uint16_t> distance;    // raw: 0..0xFFFF spans the non-ambiguous range; 0 = no return
  std::vector<std::uint16_t> amplitude;
  std::vector<std::uint16_t> confidence;  // 0xFFFF = highest; empty without AM_CONF_MAP
  Cloud cloud;                            // organized, metres, right-handed optical frame, NaN = no return
  std::chrono::system_clock::time_point timestamp;
  TofSettings settings;                   // in force when the frame was taken
  std::string device;
  std::uint32_t serial = 0;
  std::uint64_t sequence = 0;
  std::optional<DepthCameraFrame> depth_camera;  // set by depth cameras, not by the SR4000
};

// The end of a recording that does not loop (a dataset or an .oni file played once): not a device
// lost, so nothing to reconnect to.
class EndOfRecording : public Error {
 public:
  using Error::Error;
};

class TofCamera {
 public:
  virtual ~TofCamera() = default;
  virtual void configure(const TofSettings& settings) = 0;
  virtual TofSettings settings() const = 0;  // as read back from the device
  virtual TofFrame acquire() = 0;
  virtual std::string deviceString() const = 0;
  virtual std::uint32_t serial() const = 0;
};

}  // namespace keyturn::drivers

namespace keyturn::drivers {

// Per-pixel median of several frames of one camera: the raw distance's median
// sample (lower median for an even count) and that sample's point, amplitude
// and confidence; a pixel is valid when most frames saw it. Throws for none.
TofFrame medianFrame(const std::vector<TofFrame>& frames);

}  // namespace keyturn::drivers
