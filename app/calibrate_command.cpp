// keyturn calibrate-axis: the turntable's rotation axis from a captured
// sequence of the sphere target (keyturn capture --mesh builtin:sphere-target
// in simulation; a ~6 cm ball standing off-centre on a real table).
#include <cstdio>
#include <iostream>
#include <memory>

#include "commands.h"
#include "keyturn/rig/axis_calibration_run.h"
#include "progress.h"

namespace keyturn::app {
namespace {

struct CalibrateArgs {
  rig::AxisSequence sequence;
  std::string out;
};

int runCalibrate(const CalibrateArgs& a) {
  std::unique_ptr<Progress> progress;
  const rig::DatasetAxisCalibration c = rig::calibrateAxisFromDataset(
      a.sequence,
      [](const std::string& pcd, const std::string& why) {
        std::cerr << "keyturn calibrate-axis: skipping " << pcd << ": " << why << "\n";
      },
      [&progress](std::size_t done, std::size_t views) {
        if (done == 0) progress = std::make_unique<Progress>("calibrate", views, true);
        else progress->advance();
        if (done == views) progress->finish();
      });
  rig::writeAxisCalibration(a.out, c);
  const AxisCalibration& cal = c.axis;
  std::printf("axis (camera frame) %.4f %.4f %.4f through %.4f %.4f %.4f m; target circle r = %.1f mm; "
              "circle rms %.2f mm, angle rms %.2f° over %d views → %s\n",
              cal.axis.x(), cal.axis.y(), cal.axis.z(), cal.origin.x(), cal.origin.y(), cal.origin.z(),
              cal.target_radius * 1000, cal.circle_rms * 1000, cal.angle_rms_deg, cal.views, a.out.c_str());
  if (cal.reported_angles_clockwise)
    std::printf("warning: the pose source's angles grow clockwise seen from above; set \"direction\": -1 in its profile\n");
  return 0;
}

}  // namespace

Command addCalibrateCommand(CLI::App& app) {
  auto a = std::make_shared<CalibrateArgs>();
  auto* cmd = app.add_subcommand("calibrate-axis", "Fit the turntable's rotation axis from a sphere-target sequence");
  cmd->add_option("dataset", a->sequence.dataset, "Dataset holding the calibration sequence")->required();
  cmd->add_option("--class", a->sequence.cls, "Only views of this class");
  cmd->add_option("--instance", a->sequence.instance, "Only views of this instance");
  cmd->add_option("--elevation", a->sequence.elevation, "Only views at this elevation label");
  cmd->add_option("--out,-o", a->out, "Calibration JSON to write")->required();
  return {cmd, [a] { return runCalibrate(*a); }};
}

}  // namespace keyturn::app
