// keyturn: the command-line tool. Every failure ends as one line on stderr and
// a non-zero exit code.
#include <CLI/CLI.hpp>
#include <iostream>

#include "heap_reuse.h"
#include "openmp_waiting.h"
#include "commands.h"
#include "depth_image_options.h"
#include "keyturn/core/depth_image.h"
#include "keyturn/core/error.h"

#ifndef KEYTURN_VERSION
#define KEYTURN_VERSION "unknown"
#endif

int main(int argc, char** argv) {
  keyturn::app::keepFreedHeapForReuse();
  CLI::App app{"keyturn: ToF keypoint shape signatures (KPD/GKPD) and capture tools"};
  app.set_version_flag("--version", KEYTURN_VERSION);
  app.require_subcommand(1);
  using namespace keyturn::app;
  const Command commands[] = {addDescribeCommand(app), addBenchCommand(app), addRenderCommand(app),
                             addGrabCommand(app), addDevicesCommand(app), addSimCommand(app),
                             addTurntableCommand(app), addCaptureCommand(app), addVerifyCommand(app),
                             addSimulateCommand(app), addDemoCommand(app),
                             addCalibrateCommand(app), addRepeatabilityCommand(app),
                             addEvaluateCommand(app), addTrainCommand(app), addClassifyCommand(app), addEnrollCommand(app), addRecalibrateCommand(app),
                             addConsistencyCommand(app), addSlurmCommand(app),
                             addImportCommand(app), addStabilityCommand(app), addReconstructCommand(app)};
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    // A bad option is an error like any other: one line, exit 1.
    std::string where = "keyturn";
    for (const auto* sub : app.get_subcommands()) where += " " + sub->get_name();
    std::cerr << where << ": " << e.what() << " (see " << where << " --help)\n";
    return 1;
  }
  // Only reconstruct runs OpenMP teams (Open3D): the second start costs any other command 88 ms.
  // The parse has no effects, so the second start parses again what the first did.
  if (app.got_subcommand("reconstruct")) waitPassivelyInOpenMp(argv);
  try {
    for (const auto& c : commands)
      if (c.cli->parsed()) return c.run();
  } catch (const keyturn::MissingIntrinsicsError& e) {  // core names no flag; this is how to give them
    std::cerr << "keyturn: " << e.what() << " (" << kIntrinsicsHint << ")\n";
    return 1;
  } catch (const keyturn::Error& e) {
    std::cerr << "keyturn: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "keyturn: unexpected failure: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
