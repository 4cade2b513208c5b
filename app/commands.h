#pragma once
// Each keyturn subcommand registers its options and returns the function that
// runs it (exit code). Errors propagate as keyturn::Error to main.
#include <CLI/CLI.hpp>
#include <functional>

namespace keyturn::app {

struct Command {
  CLI::App* cli;            // the parsed subcommand
  std::function<int()> run; // runs it, returns the exit code
};

Command addDescribeCommand(CLI::App& app);
Command addBenchCommand(CLI::App& app);
Command addRenderCommand(CLI::App& app);
Command addGrabCommand(CLI::App& app);
Command addDevicesCommand(CLI::App& app);
Command addSimCommand(CLI::App& app);
Command addTurntableCommand(CLI::App& app);
Command addCaptureCommand(CLI::App& app);
Command addVerifyCommand(CLI::App& app);
Command addSimulateCommand(CLI::App& app);
Command addDemoCommand(CLI::App& app);
Command addCalibrateCommand(CLI::App& app);
Command addRepeatabilityCommand(CLI::App& app);
Command addEvaluateCommand(CLI::App& app);
Command addTrainCommand(CLI::App& app);
Command addClassifyCommand(CLI::App& app);
Command addEnrollCommand(CLI::App& app);
Command addRecalibrateCommand(CLI::App& app);
Command addConsistencyCommand(CLI::App& app);
Command addSlurmCommand(CLI::App& app);
Command addImportCommand(CLI::App& app);
Command addStabilityCommand(CLI::App& app);
Command addReconstructCommand(CLI::App& app);

}  // namespace keyturn::app
