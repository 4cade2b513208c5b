#pragma once
// Each keyturn subcommand registers its options and returns the function that
// runs it (exit code). Errors propagate as keyturn::Error to main.
#include <CLI/CLI.hpp>
#include <functional>

namespace keyturn::app {

using Runner = std::function<int()>;

Runner addDescribeCommand(CLI::App& app);
Runner addBenchCommand(CLI::App& app);
Runner addRenderCommand(CLI::App& app);

}  // namespace keyturn::app
