// Parameters files (docs/parameters.md): load, query at a depth with ± σ
// (estimation/parameter_query.h, what `pliant params` prints), save.
#include <filesystem>
#include <string>

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "bindings.h"
#include "pliant/estimation/identification_report.h"
#include "pliant/estimation/parameter_query.h"
#include "pliant/io/input_error.h"
#include "pliant/io/parameters_json.h"

namespace pliant::python {
namespace {

py::object AtDepth(const Parameters& parameters, double depth_m) {
  if (!(depth_m > 0.0 && depth_m <= 0.3)) {
    throw io::InputError("depth_m", 0, 0,
                         "depth " + std::to_string(depth_m) + " m is outside 0–0.3 m",
                         "give the insertion depth in metres, e.g. 0.12 for 12 cm");
  }
  return ToPython(estimation::DepthJson(estimation::QueryParametersAtDepth(parameters, depth_m)));
}

}  // namespace

void BindParameters(py::module_& m) {
  py::class_<Parameters>(m, "Parameters",
                         "A validated parameters file: per joint the compliance law K(L) "
                         "(rad/(N·m)), the backlash δ (rad), the bias torque τ0(q) (N·m), and "
                         "the covariance of what was identified. Make one with "
                         "pliant.load_parameters or pliant.parameters_from_json.")
      .def_readwrite("description", &Parameters::description, "Free text kept in the file.")
      .def_property_readonly(
          "has_covariance", [](const Parameters& p) { return p.covariance.has_value(); },
          "True when the file carries a covariance (σ of the queries is then non-zero).")
      .def("at_depth", &AtDepth, py::arg("depth_m"),
           "K1, K2 (rad/(N·m)), δ1, δ2 (rad) and 1/K1, 1/K2 (N·m/rad), each with its σ "
           "(key + '_sd'), at insertion depth depth_m (m, in (0, 0.3]): the dict "
           "`pliant params FILE --depth L --json` prints. depth_clamped is True when L is "
           "outside a joint's valid range (K is then the nearest end's); in_covariance[j] is False "
           "for a joint the file's covariance lacks (not identified: its _sd of 0 is not known). "
           "Raises InputError "
           "for a depth outside (0, 0.3] m.")
      .def(
          "to_dict", [](const Parameters& p) { return ToPython(io::ParametersToJson(p)); },
          "The parameters file's JSON as a dict (docs/parameters.md).")
      .def(
          "save",
          [](const Parameters& p, const std::filesystem::path& path) {
            io::WriteParameters(path.string(), p);
          },
          py::arg("path"), "Writes the parameters file atomically (JSON).")
      .def("__repr__", [](const Parameters& p) {
        return "<pliant.Parameters '" + p.description + "'" +
               (p.covariance ? " with covariance>" : ">");
      });
  m.def(
      "load_parameters",
      [](const std::filesystem::path& path) { return io::ReadParameters(path.string()); },
      py::arg("path"),
        "Reads and validates a parameters file (JSON). Raises InputError naming the line of "
        "a bad key.");
  m.def("parameters_from_json", &io::ParseParameters, py::arg("text"),
        py::arg("name") = "<string>",
        "Parses parameters from JSON text; `name` stands for the file in error messages.");
}

}  // namespace pliant::python
