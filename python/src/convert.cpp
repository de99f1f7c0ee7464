// Errors and JSON, the two things every binding hands to Python.
#include <pybind11/pybind11.h>

#include "bindings.h"
#include "pliant/io/input_error.h"

namespace pliant::python {

py::object ToPython(const nlohmann::json& value) {
  return py::module_::import("json").attr("loads")(value.dump());
}

py::object ToPython(const nlohmann::ordered_json& value) {
  return py::module_::import("json").attr("loads")(value.dump());
}

// io::InputError becomes pliant.InputError (a ValueError) with the same text,
// "FILE:LINE[:COLUMN]: what is wrong — what to do", and its parts as
// attributes. Other C++ exceptions keep pybind11's mapping (std::invalid_argument:
// ValueError, std::system_error and other runtime errors: RuntimeError).
void BindErrors(py::module_& m) {
  static py::exception<io::InputError> input_error(m, "InputError", PyExc_ValueError);
  input_error.doc() =
      "Bad input (a log, a parameters file, an option): the message is "
      "'FILE:LINE[:COLUMN]: what is wrong — what to do', as the pliant command prints it. "
      "Attributes: file, line, column (0 when not known), problem, fix.";
  py::register_exception_translator([](std::exception_ptr thrown) {
    try {
      if (thrown) std::rethrow_exception(thrown);
    } catch (const io::InputError& e) {
      py::object error = py::handle(input_error.ptr())(e.what());
      error.attr("file") = e.file();
      error.attr("line") = e.line();
      error.attr("column") = e.column();
      error.attr("problem") = e.problem();
      error.attr("fix") = e.fix();
      PyErr_SetObject(input_error.ptr(), error.ptr());
    }
  });
}

}  // namespace pliant::python
