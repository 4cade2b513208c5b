#pragma once
// Every tunable parameter of a view descriptor, listed once: its key in a
// feature specification (the text kept in feature caches and model sidecars and
// hashed into cache names), its command-line flag and help, and how it reads and
// writes its field of DescriptorOptions. The defaults are DescriptorOptions' own
// (and those of the structs it holds); nothing else writes them down.
//
// Adding a parameter: a field in its options struct and one row in
// core/src/descriptor_parameters.cpp. The CLI, the specification and the cache
// hash follow from the row.
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "keyturn/core/descriptor.h"

namespace keyturn {

struct DescriptorParameter {
  enum class Kind { Integer, Number, Switch, Choice };
  // Key in the feature specification; empty for a parameter that does not change
  // the features (e.g. the low-keypoint warning), which stays out of it.
  std::string key;
  // Command-line flag; a Switch is on by default and its flag turns it off ("--no-plane").
  std::string flag;
  std::string help;
  Kind kind;
  // The value as the specification writes it ("32", "0.35", "on", "fixed").
  std::function<std::string(const DescriptorOptions&)> get;
  // Parses and checks a value; throws keyturn::Error with a short reason ("must be positive, not '0'")
  // that callers prefix with the key or flag.
  std::function<void(DescriptorOptions&, const std::string&)> set;
  // For a row added after specifications were first written: the value a specification without
  // this key stands for (how its features were made), so old caches and models read as they
  // were. Empty: the key is required.
  std::string absent_means = {};
};

const std::vector<DescriptorParameter>& descriptorParameters();
// The row of a command-line flag ("--bins"); throws keyturn::Error for an unknown flag.
const DescriptorParameter& descriptorParameter(const std::string& flag);

// The parameters' specification entries (the rows with a key).
std::map<std::string, std::string> parameterSpec(const DescriptorOptions& options);
// The specification with every row added since it was written filled in with what its absence
// means (DescriptorParameter::absent_means): how an old cache's or model's features were made.
std::map<std::string, std::string> completedParameterSpec(std::map<std::string, std::string> spec);
// Sets every keyed parameter from a specification; throws keyturn::Error naming `source`
// and the key for a missing or bad entry. Parameters without a key keep their defaults.
DescriptorOptions optionsFromParameterSpec(const std::map<std::string, std::string>& spec, const std::string& source);

}  // namespace keyturn
