// keyturn from Python: the descriptors, datasets and models of the libraries as a
// module (docs/python.md). Each part lives in its own file (bindings.h).
#include "bindings.h"
#include "keyturn/core/error.h"

PYBIND11_MODULE(_keyturn, m) {
  namespace py = pybind11;
  m.doc() = "keyturn: ISS keypoint-distribution shape descriptors, datasets and models (docs/python.md)";
  m.attr("__version__") = KEYTURN_VERSION;
  // keyturn::Error carries the one-line message the command line prints.
  py::register_exception<keyturn::Error>(m, "Error", PyExc_RuntimeError);
  keyturn::python::bindClouds(m);
  keyturn::python::bindParameters(m);
  keyturn::python::bindDescribe(m);
  keyturn::python::bindDataset(m);
  keyturn::python::bindModel(m);
  keyturn::python::bindReconstruct(m);
}
