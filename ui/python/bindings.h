#pragma once
// The pieces of the `keyturn` Python module, each binding one part of the libraries.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <string>

#include "keyturn/core/cloud.h"
#include "keyturn/core/descriptor.h"
#include "keyturn/core/error.h"
#include "keyturn/learning/model_file.h"

namespace keyturn::python {

namespace py = pybind11;

// --- clouds.cpp: point clouds between numpy, Open3D and keyturn ---------------------------
// What the caller says of an array's layout: kind 'auto' (an H × W × 3 array is a frame, N × 3 a
// segmented cloud, with a warning when N × 3 looks like a frame whose grid was lost), 'frame'
// (must have its grid) or 'segmented' (the grid, if any, dropped); (height, width) when given
// puts N × 3 rows back on their pixel grid.
struct InputForm {
  enum Kind { Auto, Frame, Segmented } kind = Auto;
  std::uint32_t width = 0, height = 0;  // 0: as given
  bool warn = true;
};
// kind and shape as describe and classify take them; ValueError / TypeError for bad ones.
InputForm inputForm(const std::string& kind, const py::object& shape, const char* function);
// A view given to describe or classify: a file path (str or os.PathLike), a keyturn.Cloud, an
// Open3D point cloud (legacy or tensor) or an array N × 3 (or H × W × 3 organized, NaN for missing
// pixels). Loads files with the GIL released. `name` receives what messages call it (the path,
// or "points"). A missing file raises FileNotFoundError.
Cloud cloudFrom(const py::handle& source, const char* function, std::string* name, const InputForm& form = {});
// Raises FileNotFoundError (errno ENOENT, the path as its filename) when nothing is at `path`.
void requireFile(const std::string& path);
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
// --- model.cpp: keyturn.Model ----------------------------------------------------------------
// A model trained in Python as a keyturn.Model (`source` names it in messages until saved).
py::object wrapModel(learning::Model model, const std::string& source);
void bindModel(py::module_& m);
// --- reconstruct.cpp: keyturn.reconstruct and keyturn.Reconstruction --------------------------
void bindReconstruct(py::module_& m);

}  // namespace keyturn::python
