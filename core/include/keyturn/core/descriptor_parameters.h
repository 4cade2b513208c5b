#pragma once
// Every tunable parameter of a view descriptor, listed once: its name (its key in a
// feature specification: the text kept in feature caches and model sidecars and
// hashed into cache names), its help, and how it reads and writes its field of
// DescriptorOptions. Front ends word it from the name: the Python keyword is the
// name, the CLI's flag is made from it in app/ (descriptor_options.cpp), so core
// holds no command-line wording. The defaults are DescriptorOptions' own
// (and those of the structs it holds); nothing else writes them down.
//
// Adding a parameter: a field in its options struct and one row in
// core/src/descriptor_parameters.cpp. The CLI, Python, the specification and the
// cache hash follow from the row.
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "keyturn/core/descriptor.h"

namespace keyturn {

struct DescriptorParameter {
  enum class Kind { Integer, Number, Switch, Choice };
  // The parameter's name, and its key in the feature specification when in_spec. A Switch is
  // on by default; front ends offer to turn it off.
  std::string name;
  std::string help;
  Kind kind;
  // The value as the specification writes it ("32", "0.35", "on", "fixed").
  std::function<std::string(const DescriptorOptions&)> get;
  // Parses and checks a value; throws keyturn::Error with a short reason ("must be positive, not '0'")
  // that callers prefix with the key, the name or their own word for it.
  std::function<void(DescriptorOptions&, const std::string&)> set;
  // For a row added after specifications were first written: the value a specification without
  // this key stands for (how its features were made), so old caches and models read as they
  // were. Empty: the key is required.
  std::string absent_means = {};
  // False for a parameter that does not change the features (the low-keypoint warning): it
  // stays out of the specification.
  bool in_spec = true;
  // An option that is off by default: written only when it differs from absent_means, so the
  // default specification — hence every existing cache's name and model — is what it was before
  // the row existed (keypoint refinement).
  bool written_when_set = false;
};

const std::vector<DescriptorParameter>& descriptorParameters();
// The row of a name ("bins"); throws keyturn::Error for an unknown name.
const DescriptorParameter& descriptorParameter(const std::string& name);

// The parameters' specification entries (the rows in_spec; a written_when_set row only when set).
std::map<std::string, std::string> parameterSpec(const DescriptorOptions& options);
// The specification with every row added since it was written filled in with what its absence
// means (DescriptorParameter::absent_means): how an old cache's or model's features were made.
std::map<std::string, std::string> completedParameterSpec(std::map<std::string, std::string> spec);
// Sets every keyed parameter from a specification; throws keyturn::Error naming `source`
// and the key for a missing or bad entry. Parameters not in_spec keep their defaults.
DescriptorOptions optionsFromParameterSpec(const std::map<std::string, std::string>& spec, const std::string& source);

}  // namespace keyturn
