#pragma once
// The pieces of the `keyturn` Python module, each binding one part of the libraries.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <string>

#include "keyturn/core/cloud.h"
#include "keyturn/core/descriptor.h"
#include "keyturn/core/error.h"

namespace keyturn::python {

namespace py = pybind11;

// --- clouds.cpp: point clouds between numpy and keyturn ---------------------------------
// A view given to describe or classify: a file path (str or os.PathLike), a keyturn.Cloud,
// or an array N × 3 (or H × W × 3 organized, NaN for missing pixels). Loads files with the
// GIL released. `name` receives what messages call it (the path, or "points").
Cloud cloudFrom(const py::handle& source, const char* function, std::string* name);
// The error naming the view once ("FILE: what"), as the command line reports it.
Error namedError(const std::string& name, const Error& e);
void bindClouds(py::module_& m);

// --- parameters.cpp: the descriptor's parameter table as keyword arguments ---------------
// Options with every row named in `kwargs` set, the others at the library's defaults.
// Raises TypeError for an unknown name or a value of the wrong type, ValueError for a bad value.
DescriptorOptions optionsFrom(const py::kwargs& kwargs, const char* function);
// One docstring line per parameter: "name (default): help".
std::string parametersDoc();
void bindParameters(py::module_& m);

void bindDescribe(py::module_& m);
void bindDataset(py::module_& m);
void bindModel(py::module_& m);

}  // namespace keyturn::python
