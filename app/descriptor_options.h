#pragma once
// The descriptor's parameters on a command line: one option per row of the
// parameter table (keyturn/core/descriptor_parameters.h), bound straight to a
// DescriptorOptions, so the CLI's defaults are the library's. The flags' spelling
// is the CLI's own, made here from each row's name.
#include <CLI/CLI.hpp>
#include <map>
#include <string>

#include "keyturn/core/descriptor.h"
#include "keyturn/core/descriptor_parameters.h"

namespace keyturn::app {

// Rows whose flag is not their name's words: the name → the flag.
const std::map<std::string, std::string>& descriptorFlagExceptions();
// A row's flag: "--" and its name's words joined by '-' (a Switch's with "no-": it turns the
// setting off), unless descriptorFlagExceptions names another: bins → --bins, filter →
// --no-filter, extent_m → --extent.
std::string descriptorFlag(const DescriptorParameter& p);

struct DescriptorFlags {
  DescriptorOptions options;

  // with_features = false: the dataset tools, whose feature cache holds every block.
  void add(CLI::App& cmd, bool with_features = true);
  const DescriptorOptions& toOptions() const { return options; }
};

}  // namespace keyturn::app
