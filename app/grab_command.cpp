// keyturn grab: frames from an SR4000 (or the simulated one) to an organized
// PCD plus 16-bit PNGs of raw distance, amplitude and confidence.
#include <iostream>

#include "commands.h"
#include "device_options.h"
#include "keyturn/rig/device_factory.h"
#include "keyturn/rig/frame_files.h"
#include "keyturn/core/error.h"
#include "progress.h"

namespace keyturn::app {
namespace {

struct GrabArgs {
  std::string camera = "sim";
  std::string sim_config;
  std::string library;
  std::string out;
  int frames = 1;
  int integration_time = -1;
  bool no_auto_exposure = false;
  double modulation_mhz = 30.0;
  int amplitude_threshold = -1;
  int distance_offset = -1;
  std::string mode;
};

int runGrab(const GrabArgs& a) {
  rig::DeviceFactory factory;
  auto cam = factory.openCamera(cameraSpec(a.camera, a.library, a.sim_config));
  drivers::TofSettings s = cam->settings();
  if (a.integration_time >= 0) s.integration_time = static_cast<std::uint8_t>(a.integration_time);
  s.auto_exposure.enabled = !a.no_auto_exposure && a.integration_time < 0;
  s.modulation_frequency = drivers::modulationIndex(a.modulation_mhz);
  if (a.amplitude_threshold >= 0) s.amplitude_threshold = static_cast<std::uint16_t>(a.amplitude_threshold);
  if (a.distance_offset >= 0) s.distance_offset = static_cast<std::uint16_t>(a.distance_offset);
  if (!a.mode.empty()) {
    try {
      s.acquire_mode = static_cast<std::uint32_t>(std::stoul(a.mode, nullptr, 0));
    } catch (const std::exception&) {
      throw Error("--mode: '" + a.mode + "' is not a number (e.g. 0x911)");
    }
  }
  cam->configure(s);

  std::vector<drivers::TofFrame> frames;
  Progress progress("grab", static_cast<std::size_t>(a.frames), a.frames > 1);
  for (int i = 0; i < a.frames; ++i) {
    frames.push_back(cam->acquire());
    progress.advance();
  }
  progress.finish();
  const drivers::TofFrame f = drivers::medianFrame(frames);
  const auto written = rig::writeFrameFiles(a.out, f);
  std::cerr << "keyturn grab: " << cam->deviceString() << ", serial " << cam->serial() << ": " << a.frames
            << (a.frames > 1 ? " frames (per-pixel median)" : " frame") << ", " << f.cloud.validCount() << " of "
            << f.cloud.size() << " pixels with a return, ";
  if (f.depth_camera) {  // a depth camera: its pinhole, not the SR4000's modulation
    const DepthIntrinsics& k = f.depth_camera->intrinsics;
    std::cerr << "depth in " << f.depth_camera->depth_unit_m * 1000 << " mm units, fx " << k.fx << " fy " << k.fy
              << " cx " << k.cx << " cy " << k.cy << (f.depth_camera->registered ? ", registered to colour" : "")
              << "\n";
  } else {
    std::cerr << drivers::modulationMHz(f.settings.modulation_frequency) << " MHz (range "
              << drivers::nonAmbiguousRange(f.settings.modulation_frequency) << " m)\n";
  }
  for (const auto& p : written) std::cout << p << "\n";
  return 0;
}

}  // namespace

Command addGrabCommand(CLI::App& app) {
  auto a = std::make_shared<GrabArgs>();
  auto* cmd = app.add_subcommand("grab", "Grab SR4000 or OpenNI2 frames to an organized PCD and 16-bit PNGs");
  cmd->add_option("--camera", a->camera, "sim, sim:CONFIG, usb, usb:SERIAL, eth:IP, openni2[:URI], playback:DATASET[@FPS] or playback:FILE.oni")->capture_default_str();
  cmd->add_option("--mesasr-lib", a->library,
                  "Path of MESA's libmesasr.so for usb/eth (default: $KEYTURN_MESASR_LIB, then the usual sonames)");
  // $MESASR_SIM_CONFIG, libmesasr-sim's own variable for outside programs, is read here only as this
  // flag's default: the configuration reaches the simulator in the camera's spec, not the environment.
  cmd->add_option("--sim-config", a->sim_config, "Simulator configuration JSON for --camera sim (default: $MESASR_SIM_CONFIG)")
      ->envname("MESASR_SIM_CONFIG");
  cmd->add_option("--out,-o", a->out, "PCD to write; PNGs are written beside it")->required();
  cmd->add_option("--frames,-n", a->frames, "Frames to take; more than one gives their per-pixel median")
      ->capture_default_str()->check(CLI::Range(1, 10000));
  cmd->add_option("--integration-time", a->integration_time, "0-255 (0.3 ms + n × 0.1 ms); turns auto-exposure off")
      ->check(CLI::Range(0, 255));
  cmd->add_flag("--no-auto-exposure", a->no_auto_exposure, "Fixed integration time");
  cmd->add_option("--modulation", a->modulation_mhz, "Modulation frequency in MHz")->capture_default_str();
  cmd->add_option("--amplitude-threshold", a->amplitude_threshold, "Pixels below it read no distance")
      ->check(CLI::Range(0, 65535));
  cmd->add_option("--distance-offset", a->distance_offset, "Raw distance offset")->check(CLI::Range(0, 65535));
  cmd->add_option("--mode", a->mode, "Acquire-mode flags (default 0x911: fixed-pattern, gray, ANF, confidence)");
  return {cmd, [a] { return runGrab(*a); }};
}

}  // namespace keyturn::app
