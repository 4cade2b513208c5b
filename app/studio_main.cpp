// keyturn-studio: the capture and live-recognition GUI.
//
//   keyturn-studio                 devices as last used (Devices panel)
//   keyturn-studio --simulated     the simulated rig and the built-in model, connected at once
//   keyturn-studio --playback DATASET  a dataset replayed as camera and turntable, with the built-in model
//   keyturn-studio --simulated --measure 20 --screenshot live.png
//                                  run 20 s, print the measured rates as JSON, save the window
#include <CLI/CLI.hpp>
#include <QApplication>
#include <cstdlib>
#include <iostream>
#include <optional>

#include "heap_reuse.h"
#include "openmp_waiting.h"
#include "keyturn/core/error.h"
#include "keyturn/core/install_layout.h"
#include "keyturn/rig/dataset_playback.h"
#include "keyturn/studio/studio_rig_factory.h"
#include "keyturn/studio/studio_session.h"


namespace {

struct Args {
  bool simulated = false;
  std::string object, model, dataset, settings, screenshot, playback, camera;
  double playback_rate = 0;
  bool playback_once = false;
  int threads = 2;
  bool start_capture = false, paths = false;
  double measure = 0;
};

}  // namespace

int main(int argc, char** argv) {
  // Reconstruct… runs Open3D beside the camera and recognition threads: a second start, once.
  keyturn::app::waitPassivelyInOpenMp(argv);
  keyturn::app::keepFreedHeapForReuse();
  keyturn::studio::catchQuitSignals();
  Args a;
  CLI::App cli("keyturn studio: live ToF capture on a turntable rig and keypoint-based recognition");
  auto* simulated = cli.add_flag("--simulated", a.simulated, "Start with the simulated SR4000 and turntable connected and the built-in model");
  cli.add_option("--playback", a.playback,
                 "Replay this dataset (captured, simulated or imported) as the camera and the turntable, with the built-in "
                 "model unless --model")
      ->excludes(simulated);
  cli.add_option("--playback-rate", a.playback_rate, "Frames per second of the playback (default: as recorded)")
      ->check(CLI::PositiveNumber);
  cli.add_flag("--playback-once", a.playback_once, "Stop at the end of the recording instead of starting over");
  cli.add_option("--camera", a.camera,
                 "Start with this camera connected, named as keyturn grab names it (openni2, openni2:URI, "
                 "playback:FILE.oni, usb, eth:IP)")
      ->excludes(simulated);
  cli.add_option("--object", a.object,
                 "Instance on the simulated turntable (data/objects/objects-27.csv: the built-in model's 15 and 12 it "
                 "never saw), e.g. ycb_035_power_drill");
  cli.add_option("--model", a.model, "Model folder (keyturn train --out …); with --simulated or --playback the built-in one by default");
  cli.add_option("--dataset", a.dataset, "Capture dataset folder");
  cli.add_option("--threads", a.threads, "Recognition threads")->capture_default_str()->check(CLI::Range(1, 16));
  cli.add_flag("--start-capture", a.start_capture, "Start the capture sequence as soon as camera and turntable answer");
  cli.add_flag("--geodesic-paths", a.paths, "Show the geodesic paths (centre → keypoints) in the 3D view");
  cli.add_option("--settings", a.settings, "Settings file (INI) instead of the user's");
  cli.add_option("--measure", a.measure, "Run this many seconds after a 3 s warm-up, print the rates as JSON, quit")
      ->check(CLI::PositiveNumber);
  cli.add_option("--screenshot", a.screenshot, "Save the window as PNG before quitting (with --measure)");
  // keyturn's options first (so --help works anywhere); Qt's own (-platform, …) pass through.
  cli.allow_extras();
  try {
    cli.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return cli.exit(e);  // --help
    std::cerr << "keyturn-studio: " << e.what() << " (see keyturn-studio --help)\n";
    return 1;
  }
  std::string data;
  try {
    data = keyturn::dataDirectory().string();
  } catch (const keyturn::Error& e) {
    std::cerr << "keyturn-studio: " << e.what() << "\n";
    return 1;
  }
  // The simulated turntable offers the 27 objects: the built-in model knows the first 15
  // (objects.csv) and answers "unknown" for the others.
  const std::string objects_csv = data + "/objects/objects-27.csv";
  keyturn::studio::StudioRigFactory factory(objects_csv);
  // Refused here: the window would otherwise fall back to the object used last.
  if (const std::string bad = keyturn::studio::unknownSimObject(factory.simObjects(), a.object, objects_csv);
      !a.object.empty() && !bad.empty()) {
    std::cerr << "keyturn-studio: " << bad << "\n";
    return 1;
  }
  // A recording that cannot be played is said here, in one line, not in a window.
  if (!a.playback.empty()) {
    try {
      keyturn::rig::Recording check(a.playback, {a.playback_rate, !a.playback_once});
    } catch (const keyturn::Error& e) {
      std::cerr << "keyturn-studio: " << e.what() << "\n";
      return 1;
    }
  }
  std::optional<keyturn::rig::CameraSpec> camera;
  if (!a.camera.empty()) {
    try {
      camera = keyturn::rig::CameraSpec::parse(a.camera);
    } catch (const keyturn::Error& e) {
      std::cerr << "keyturn-studio: " << e.what() << "\n";
      return 1;
    }
  }
  if (!std::getenv("DISPLAY") && !std::getenv("WAYLAND_DISPLAY") && !std::getenv("QT_QPA_PLATFORM")) {
    std::cerr << "keyturn-studio: no display (DISPLAY is not set): run it on a desktop, or headless as "
                 "xvfb-run -a keyturn-studio …\n";
    return 1;
  }
  QApplication app(argc, argv);
  keyturn::studio::StudioOptions o;
  o.simulated = a.simulated;
  o.sim_object = a.object;
  o.model = a.model.empty() && (a.simulated || !a.playback.empty()) ? data + "/models/sim-objects" : a.model;
  o.playback = {a.playback, a.playback_rate, !a.playback_once};
  o.camera = camera;
  o.dataset = a.dataset;
  o.recognition_threads = a.threads;
  o.settings_file = a.settings;
  o.start_capture = a.start_capture;
  o.geodesic_paths = a.paths;
  keyturn::studio::StudioWindow window(factory, o);
  window.show();
  keyturn::studio::closeOnQuitSignal(window);
  if (a.measure > 0) keyturn::studio::measureThenQuit(window, a.measure, a.threads, a.screenshot);
  return app.exec();
}
