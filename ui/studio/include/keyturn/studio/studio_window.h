#pragma once
// keyturn studio's main window: devices, live images, the 3D view, capture
// and live recognition. Acquisition, the pose readout and recognition run on
// their own threads; the window only shows what they report. It lays out the
// panels and connects three controllers, each owning its own state: the
// devices (worker threads, problem banner), the live view (frames, results,
// rates, redraw clock, model) and the capture (sequence start, snapshot).
#include <QMainWindow>
#include <array>
#include <memory>
#include <optional>

#include "keyturn/studio/rig_factory.h"

class QAction;
class QDockWidget;
class QSettings;

namespace keyturn::studio {

struct StudioOptions {
  bool simulated = false;        // start with the simulated rig connected
  std::string sim_object;        // instance on the simulated turntable ("" = the first)
  std::string model;             // model folder to load at start ("" = the saved one)
  std::string dataset;           // capture folder ("" = the saved one)
  int recognition_threads = 2;
  std::string settings_file;     // "" = the user's (QSettings keyturn/studio)
  bool start_capture = false;    // start the capture sequence once camera and turntable are up
  bool geodesic_paths = false;   // show the geodesic paths in the 3D view from the start
  rig::PlaybackSpec playback;    // dataset not empty: start playing it back as camera and pose source
  std::optional<rig::CameraSpec> camera;  // start with this camera connected (no pose source)
};

// Live numbers, for the status bar, tests and `keyturn-studio --measure`.
struct StudioRates {
  double camera_fps = 0, recognition_fps = 0, latency_ms = 0, describe_ms = 0;
  long frames = 0, results = 0, dropped = 0;
};

// The reconstructed model in the 3D view (Reconstruct), for tests.
struct ShownModel {
  bool shown = false;  // false: the live cloud is shown
  int vertices = 0, triangles = 0;
  std::array<double, 6> bounds{};  // x min, x max, y min, y max, z min, z max (metres)
};

class BackgroundJob;
class CaptureController;
class CapturePanel;
class CloudView;
class DeviceController;
class DevicesPanel;
class EnrollController;
class ReconstructController;
class LiveView;
class RecognitionPanel;

class StudioWindow : public QMainWindow {
  Q_OBJECT
 public:
  StudioWindow(RigFactory& factory, StudioOptions options, QWidget* parent = nullptr);
  ~StudioWindow() override;

  StudioRates rates() const;
  QString bannerText() const;    // "" when no banner is shown
  QString recognisedClass() const;
  double recognisedAgreement() const;
  // The belief fused over the views of the table's turn: its answer ("" before any view), the
  // answer's belief and the views fused.
  QString fusedClass() const;
  double fusedBelief() const;
  int fusedViews() const;
  ShownModel shownModel() const;

 protected:
  void closeEvent(QCloseEvent* e) override;

 private:
  void buildLayout(RigFactory& factory, int recognition_threads);
  void buildToolbar(CloudView* cloud);
  void buildModelActions(CloudView* cloud);
  void placeWindow();
  void connectDevices(RigFactory& factory);  // open what the options name
  void startCaptureWhenReady();

  StudioOptions options_;
  std::unique_ptr<QSettings> settings_;
  // The panels whose settings the window saves and restores (owned by their docks).
  DevicesPanel* devices_panel_ = nullptr;
  CapturePanel* capture_panel_ = nullptr;
  RecognitionPanel* recognition_panel_ = nullptr;
  QDockWidget* capture_dock_ = nullptr;
  QAction* show_model_ = nullptr;
  CloudView* cloud_ = nullptr;
  // Destroyed in reverse: the capture, then the device threads (a capture ends after its view),
  // then the recognition threads — all before the widgets they draw into.
  std::unique_ptr<LiveView> live_;
  std::unique_ptr<DeviceController> devices_;
  std::unique_ptr<CaptureController> capture_;
  // Last: a running reconstruction or enrollment is waited for first.
  std::unique_ptr<BackgroundJob> job_;
  std::unique_ptr<ReconstructController> reconstruct_;
  std::unique_ptr<EnrollController> enroll_;
};

}  // namespace keyturn::studio
