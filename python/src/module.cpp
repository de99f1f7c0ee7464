// _pliant: the compiled half of the pliant Python package (python/pliant/
// __init__.py is the other half and the documented entry point).
#include <pybind11/pybind11.h>

#include "bindings.h"

PYBIND11_MODULE(_pliant, m) {
  m.doc() = "pliant's C++ libraries: logs, parameters, correct, identify, diagnose, filter";
  pliant::python::BindErrors(m);
  pliant::python::BindLogs(m);
  pliant::python::BindParameters(m);
  pliant::python::BindCorrect(m);
  pliant::python::BindIdentify(m);
  pliant::python::BindDiagnose(m);
  pliant::python::BindFilter(m);
}
