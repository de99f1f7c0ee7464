#pragma once
// The pieces of the pliant Python module (_pliant), one Bind function per
// area. Each is a thin layer over the C++ libraries: no estimation here.

#include <string>

#include <nlohmann/json.hpp>
#include <pybind11/pybind11.h>

#include "pliant/estimation/tip_error_statistics.h"
#include "pliant/models/parameters.h"

namespace pliant::python {

namespace py = pybind11;

void BindErrors(py::module_& m);
void BindLogs(py::module_& m);
void BindParameters(py::module_& m);
void BindCorrect(py::module_& m);
void BindIdentify(py::module_& m);
void BindDiagnose(py::module_& m);
void BindFilter(py::module_& m);

/// A JSON value as the same Python object json.loads would give (dict, list,
/// float, …): the libraries' reports reach Python unchanged, to the last digit.
py::object ToPython(const nlohmann::json& value);
py::object ToPython(const nlohmann::ordered_json& value);

/// The parameters held by a Python pliant.Parameters object.
using Parameters = models::ModelParameters;

/// {"rows": n, "rms_mm": …, "max_mm": …}: tip error against the log's reference, mm.
py::dict TipErrorDict(const estimation::TipErrorStatistics& statistics);

/// `--tare SPEC` of pliant correct and pliant filter (estimation/log_tare.h):
/// `parameters` tared on the log at `input` ("" leaves them), the note
/// appended to `metadata_note`; returns the summary's lines ("" untared).
std::string TareForLog(const std::string& input, const std::string& spec, Parameters* parameters,
                       std::string* metadata_note);
}  // namespace pliant::python
