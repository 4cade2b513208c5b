#pragma once
// How keyturn-studio runs a session around its window: Ctrl-C and SIGTERM close
// it as its close button does, a --object is checked against the simulated
// objects, and --measure runs it for a while and prints its rates as JSON.
#include <string>
#include <vector>

#include "keyturn/studio/rig_factory.h"
#include "keyturn/studio/studio_window.h"

namespace keyturn::studio {

// Ctrl-C and SIGTERM close the window as its close button does (settings saved, devices closed,
// the simulator's temporary folder removed) instead of killing the process mid-frame. A SIGINT
// ignored from the start (a background job of a script) stays ignored. catchQuitSignals first
// thing in main, so a signal during start-up is kept; closeOnQuitSignal once the window exists.
void catchQuitSignals();
void closeOnQuitSignal(QWidget& window);

// "" when instance is one of the objects, else the line that says so, naming the list and its instances.
std::string unknownSimObject(const std::vector<SimObject>& objects, const std::string& instance,
                             const std::string& objects_csv);

// After a warm-up, run `seconds`, print {"seconds", "camera_fps", …, "agreement"} on stdout, save the
// window as PNG to screenshot (unless empty), then close it and quit the application.
void measureThenQuit(StudioWindow& window, double seconds, int threads, const std::string& screenshot,
                     double warmup_s = 3.0);

}  // namespace keyturn::studio
