#pragma once
// Commodity depth cameras (Kinect, Xtion, Astra) through OpenNI2, and OpenNI2's .oni recordings
// played back as a camera (its libOniFile driver). OpenNI2's headers stay in the .cpp.
//
// A frame is the depth stream as an organized cloud (metres, x right, y down, z forward; NaN where
// the depth is 0) made with the device's pinhole: OpenNI2 gives no calibration through its generic
// API, so the intrinsics come from the stream's fields of view and resolution: fx = width / (2 tan(HFOV / 2)),
// the principal point at the image's centre, (width − 1) / 2 in 0-based pixel coordinates, as PCL's
// OpenNI2 grabber has it (OpenNI2's CoordinateConverter puts it half a pixel off). Depth is registered to
// the colour image where the device supports it; IR (as the frame's amplitude) and colour are read
// when the device has them. A stream that stops delivering frames closes and reopens the device with
// backoff (drivers/retry.h), reported through the log, before acquire gives up — as the SR4000 does.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "keyturn/core/depth_image.h"
#include "keyturn/drivers/tof_camera.h"

namespace keyturn::drivers {

// The pinhole of an image of width × height pixels seeing hfov × vfov radians, centred on the image
// (cx = (width − 1) / 2, cy = (height − 1) / 2). Throws keyturn::Error for a field of view outside
// (0, π) or an empty image.
DepthIntrinsics intrinsicsFromFieldOfView(double hfov_rad, double vfov_rad, std::uint32_t width,
                                          std::uint32_t height);

// An OpenNI2 depth image (row stride in bytes, as OpenNI2 hands it over) as a frame: its depth in
// `distance`, its organized cloud made with `intrinsics` at depth_unit_m metres per unit.
TofFrame depthCameraFrame(const std::uint16_t* depth, std::uint32_t width, std::uint32_t height,
                          std::size_t stride_bytes, const DepthIntrinsics& intrinsics, double depth_unit_m);

struct OpenNi2VideoMode {
  int width = 0, height = 0, fps = 0;
  std::string pixel_format;  // "depth 1 mm", "depth 100 um", "rgb888", "gray16", …
};

struct OpenNi2DeviceInfo {
  std::string uri, vendor, name;
  int usb_vendor_id = 0, usb_product_id = 0;
  std::vector<OpenNi2VideoMode> depth_modes;
  OpenNi2VideoMode depth_mode;          // the mode the depth stream opens in
  double hfov_deg = 0, vfov_deg = 0;    // the depth stream's fields of view
  DepthIntrinsics intrinsics;           // at depth_mode's resolution
  bool has_colour = false, has_ir = false, registration = false;
  std::string error;                    // set when the device is listed but cannot be opened
};

// The OpenNI2 devices present (OpenNI2's drivers folder decides which kinds), each opened briefly
// for its depth modes and fields of view, the one a camera without a URI opens first. Throws
// keyturn::Error when OpenNI2 cannot start.
std::vector<OpenNi2DeviceInfo> listOpenNi2Devices();

// The device a camera without a URI opens, of the URIs OpenNI2 lists: the first real device, and
// keyturn's simulated camera (keyturn-sim://…) only when no real one is there. "" for none.
std::string firstOpenNi2Device(const std::vector<std::string>& uris);

struct OpenNi2Options {
  std::string uri;            // the device's URI; empty: the first device found (firstOpenNi2Device)
  std::string oni_file;       // instead of a device: an .oni recording (libOniFile)
  double playback_fps = 0;    // .oni: 0 plays at the recorded rate
  bool loop = true;           // .oni: false ends with EndOfRecording after the last frame
  bool colour = true;         // open the colour stream where there is one (and register depth to it)
  bool ir = true;             // open the IR stream where there is one and the device streams it with depth
  int timeout_ms = 2000;      // a frame later than this counts as the device not answering
  int reconnect_attempts = 3;
  int backoff_initial_ms = 200;  // doubled per attempt
  std::function<void(const std::string&)> log;  // retries and reopens are reported here
};

class OpenNi2Camera final : public TofCamera {
 public:
  // Throws keyturn::Error in one line: no OpenNI2 device, the URI not found (naming those present),
  // an .oni file missing or unreadable (naming it), a device without a depth stream.
  explicit OpenNi2Camera(OpenNi2Options options);
  ~OpenNi2Camera() override;

  // The SR4000's settings do not apply: kept and returned, the device is left as it is.
  void configure(const TofSettings& settings) override { settings_ = settings; }
  TofSettings settings() const override { return settings_; }
  TofFrame acquire() override;
  std::string deviceString() const override;
  std::uint32_t serial() const override { return 0; }

  const OpenNi2DeviceInfo& info() const;
  int reconnects() const { return reconnects_; }

 private:
  struct Streams;
  void open();
  void close();
  TofFrame acquireOnce();
  std::string name() const;

  OpenNi2Options options_;
  TofSettings settings_;
  std::unique_ptr<Streams> s_;
  std::uint64_t sequence_ = 0;
  int reconnects_ = 0;
};

}  // namespace keyturn::drivers
