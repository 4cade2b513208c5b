#pragma once
// The descriptor's parameters on a command line: one option per row of the
// parameter table (keyturn/core/descriptor_parameters.h), bound straight to a
// DescriptorOptions, so the CLI's defaults are the library's.
#include <CLI/CLI.hpp>

#include "keyturn/core/descriptor.h"

namespace keyturn::app {

struct DescriptorFlags {
  DescriptorOptions options;

  // with_features = false: the dataset tools, whose feature cache holds every block.
  void add(CLI::App& cmd, bool with_features = true);
  const DescriptorOptions& toOptions() const { return options; }
};

}  // namespace keyturn::app
