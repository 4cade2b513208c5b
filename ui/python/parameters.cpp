// The descriptor's parameters as Python keyword arguments: one per row of the
// parameter table (keyturn/core/descriptor_parameters.h), read and checked by the
// row itself, so the defaults and the checks are the library's, as on the command line.
#include <cstdio>

#include "bindings.h"
#include "keyturn/core/descriptor_parameters.h"

namespace keyturn::python {
namespace {

using Kind = DescriptorParameter::Kind;

// A row's Python keyword: its name.
const std::string& pythonName(const DescriptorParameter& p) { return p.name; }

const char* typeName(Kind k) {
  switch (k) {
    case Kind::Integer: return "an int";
    case Kind::Number: return "a number";
    case Kind::Switch: return "a bool";
    default: return "a str";
  }
}

// The value as the row's text (what the command line would pass); false for a value of the wrong type.
bool valueText(const DescriptorParameter& p, const py::handle& v, std::string& text) {
  const bool is_bool = py::isinstance<py::bool_>(v);
  switch (p.kind) {
    case Kind::Integer:
      if (is_bool || !py::isinstance<py::int_>(v)) return false;
      text = py::str(v);
      return true;
    case Kind::Number:
      if (is_bool) return false;
      if (py::isinstance<py::int_>(v)) {
        text = py::str(v);
        return true;
      }
      if (!py::isinstance<py::float_>(v)) return false;
      {
        // 17 significant digits: the text parses back to the very same double.
        char b[40];
        std::snprintf(b, sizeof b, "%.17g", v.cast<double>());
        text = b;
      }
      return true;
    case Kind::Switch:
      if (!is_bool) return false;
      text = v.cast<bool>() ? "on" : "off";
      return true;
    default:
      if (!py::isinstance<py::str>(v)) return false;
      text = v.cast<std::string>();
      return true;
  }
}

py::object defaultValue(const DescriptorParameter& p) {
  const std::string t = p.get(DescriptorOptions());
  switch (p.kind) {
    case Kind::Integer: return py::int_(std::stoll(t));
    case Kind::Number: return py::float_(std::stod(t));
    case Kind::Switch: return py::bool_(t == "on");
    default: return py::str(t);
  }
}

std::string names() {
  std::string s;
  for (const auto& p : descriptorParameters()) s += (s.empty() ? "" : ", ") + pythonName(p);
  return s;
}

}  // namespace

DescriptorOptions optionsFrom(const py::kwargs& kwargs, const char* function) {
  DescriptorOptions o;
  for (const auto& [key, value] : kwargs) {
    const std::string name = py::str(key);
    const DescriptorParameter* row = nullptr;
    for (const auto& p : descriptorParameters())
      if (pythonName(p) == name) row = &p;
    if (!row)
      throw py::type_error(std::string(function) + "() got an unexpected keyword argument '" + name +
                           "' (parameters: " + names() + ")");
    std::string text;
    if (!valueText(*row, value, text))
      throw py::type_error(std::string(function) + ": " + name + " must be " + typeName(row->kind) + ", not " +
                           std::string(py::str(py::type::of(value).attr("__name__"))));
    try {
      row->set(o, text);
    } catch (const Error& e) {
      throw py::value_error(std::string(function) + ": " + name + " " + e.what());
    }
  }
  return o;
}

std::string parametersDoc() {
  std::string s;
  for (const auto& p : descriptorParameters())
    s += "    " + pythonName(p) + " (" + std::string(py::repr(defaultValue(p))) + "): " +
         (p.kind == Kind::Switch ? "False: " : "") + p.help + "\n";
  return s;
}

void bindParameters(py::module_& m) {
  m.def(
      "parameters",
      [] {
        py::dict d;
        for (const auto& p : descriptorParameters()) {
          py::dict row;
          row["default"] = defaultValue(p);
          row["help"] = (p.kind == Kind::Switch ? "False: " : "") + p.help;
          row["spec_key"] = p.in_spec ? py::object(py::str(p.name)) : py::object(py::none());
          d[py::str(pythonName(p))] = row;
        }
        return d;
      },
      "The descriptor's parameters (describe's and Dataset.features' keyword arguments): name → default, help and "
      "the feature-specification key. The library's own table and defaults.");
}

}  // namespace keyturn::python
