// keyturn render: a simulated SR4000 view of a mesh on the turntable, written
// as an organized PCD (x, y, z, amplitude, confidence).
#include <iostream>

#include "commands.h"
#include "keyturn/core/string_format.h"
#include "keyturn/sim/view_series.h"

namespace keyturn::app {
namespace {

struct RenderArgs {
  sim::ViewSeries series;
  std::string angles = "0";
  bool no_noise = false;
};

int runRender(RenderArgs a) {
  a.series.angles = parseNumberList(a.angles, "--angles");
  a.series.noise = !a.no_noise;
  sim::renderSeries(a.series, [&a](const std::string& path, const Cloud& c, double distance, double angle) {
    std::cerr << "keyturn render: " << path << ": " << c.validCount() << " valid of " << c.size()
              << " px, camera at " << distance << " m, elevation " << a.series.elevation_deg << "°, turntable "
              << angle << "°\n";
  });
  return 0;
}

}  // namespace

Command addRenderCommand(CLI::App& app) {
  auto args = std::make_shared<RenderArgs>();
  auto* cmd = app.add_subcommand("render", "Render a simulated SR4000 view of a mesh on a turntable (organized PCD)");
  cmd->add_option("mesh", args->series.mesh, "Mesh (PLY/OBJ/STL/OFF; metres, z up, base on z = 0), builtin:mug or builtin:sphere-target")->required();
  cmd->add_option("--out,-o", args->series.out, "PCD to write; {angle} is replaced by the turntable angle in whole degrees, 3 digits (045)")->required();
  cmd->add_option("--angles", args->angles, "Comma-separated turntable angles in degrees")->capture_default_str();
  cmd->add_option("--elevation", args->series.elevation_deg, "Camera elevation above the turntable (degrees)")->capture_default_str();
  cmd->add_option("--distance", args->series.distance,
                  "Camera to object centre (m); default: the object spans ~60% of the vertical field, 0.45–5 m");
  cmd->add_option("--seed", args->series.seed, "Noise seed")->capture_default_str();
  cmd->add_flag("--no-noise", args->no_noise, "Exact ranges (no sensor noise)");
  return {cmd, [args] { return runRender(*args); }};
}

}  // namespace keyturn::app
