// The paper's correction (equation 2) and its dead-zone form
// (estimation/compliance_correction.h) on arrays, and on log files through
// estimation::CorrectLog, the function `pliant correct` runs.
#include <limits>
#include <optional>
#include <string>

#include <pybind11/numpy.h>

#include "bindings.h"
#include "pliant/estimation/log_tare.h"
#include "pliant/estimation/effect_inputs.h"
#include "pliant/estimation/log_correction.h"
#include "pliant/io/input_error.h"

namespace pliant::python {
namespace {

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

estimation::CorrectionModel ModelNamed(const std::string& name) {
  const auto model = estimation::ParseCorrectionModel(name);
  if (!model) {
    throw io::InputError("model", 0, 0, "unknown correction model '" + name + "'",
                         "use 'paper' (equation 2) or 'deadzone' (docs/correction.md)");
  }
  return *model;
}

// An optional array (None: absent) of n values.
std::optional<Array> OptionalArray(const py::object& given, const char* name, py::ssize_t n) {
  if (given.is_none()) return std::nullopt;
  Array a = given.cast<Array>();
  if (a.ndim() > 1 || a.size() != n) {
    throw io::InputError(name, 0, 0,
                         "holds " + std::to_string(a.size()) + " values and q1 " + std::to_string(n),
                         "give it as a 1-D array of q1's length, or leave it out");
  }
  return a;
}

py::dict CorrectArrays(const Parameters& parameters, const Array& q1, const Array& q2,
                       const Array& q3, const Array& tau1, const Array& tau2,
                       const std::string& model, const py::object& t, const py::object& v1,
                       const py::object& v2) {
  const estimation::ComplianceCorrector corrector(parameters, ModelNamed(model));
  const py::ssize_t n = q1.size();
  const char* names[] = {"q1", "q2", "q3", "tau1", "tau2"};
  const Array* inputs[] = {&q1, &q2, &q3, &tau1, &tau2};
  for (int i = 0; i < 5; ++i) {
    if (inputs[i]->ndim() > 1 || inputs[i]->size() != n) {
      throw io::InputError(names[i], 0, 0,
                           "holds " + std::to_string(inputs[i]->size()) + " values and q1 " +
                               std::to_string(n),
                           "give q1, q2, q3, tau1, tau2 as 1-D arrays of the same length");
    }
  }
  // With the times, the rows are a stream: the file's effects read each
  // row's time, velocity and effort rate as `pliant correct` gives them.
  const auto time = OptionalArray(t, "t", n);
  const auto velocity1 = OptionalArray(v1, "v1", n), velocity2 = OptionalArray(v2, "v2", n);
  estimation::EffectInputs rows;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  Array q1_corr(n), q2_corr(n), tau1_ext(n), tau2_ext(n);
  py::array_t<bool> clamped(n);
  for (py::ssize_t k = 0; k < n; ++k) {
    const Eigen::Vector3d q(q1.at(k), q2.at(k), q3.at(k));
    const Eigen::Vector2d effort(tau1.at(k), tau2.at(k));
    const auto c =
        time ? corrector.Correct(rows.Update(time->at(k), q, effort,
                                             {velocity1 ? velocity1->at(k) : nan,
                                              velocity2 ? velocity2->at(k) : nan}),
                                 effort)
             : corrector.Correct(q, effort);
    q1_corr.mutable_at(k) = c.corrected_rad[0];
    q2_corr.mutable_at(k) = c.corrected_rad[1];
    tau1_ext.mutable_at(k) = c.external_torque_nm[0];
    tau2_ext.mutable_at(k) = c.external_torque_nm[1];
    clamped.mutable_at(k) = c.depth_clamped;
  }
  py::dict out;
  out["q1_corr"] = q1_corr, out["q2_corr"] = q2_corr;
  out["tau1_ext"] = tau1_ext, out["tau2_ext"] = tau2_ext;
  out["depth_clamped"] = clamped;
  return out;
}

py::dict CorrectFile(Parameters parameters, const std::string& input, const std::string& output,
                     const std::string& model, std::string metadata_note, const std::string& tare,
                     bool skip_bad_rows) {
  const std::string tared = TareForLog(input, tare, &parameters, &metadata_note);
  const estimation::ComplianceCorrector corrector(parameters, ModelNamed(model));
  estimation::LogCorrectionSummary s;
  {
    py::gil_scoped_release unlocked;
    s = estimation::CorrectLog(input, output, corrector, metadata_note, {skip_bad_rows});
  }
  py::dict out;
  out["rows"] = s.rows, out["skipped_rows"] = s.skipped_rows;
  out["depth_clamped_rows"] = s.depth_clamped_rows;
  out["reference"] = s.reference;
  out["uncorrected"] = TipErrorDict(s.uncorrected);
  out["corrected"] = TipErrorDict(s.corrected);
  out["tare"] = tared;
  return out;
}

}  // namespace

std::string TareForLog(const std::string& input, const std::string& spec, Parameters* parameters,
                       std::string* metadata_note) {
  if (spec.empty()) return "";
  const estimation::LogTare tare = estimation::TareOnLog(input, spec, parameters);
  const std::string note = tare.Note();
  if (!note.empty()) *metadata_note += ", " + note;
  return tare.Words();
}

py::dict TipErrorDict(const estimation::TipErrorStatistics& statistics) {
  py::dict out;
  out["rows"] = statistics.count();
  out["rms_mm"] = statistics.RmsMm();
  out["max_mm"] = statistics.MaxMm();
  return out;
}

void BindCorrect(py::module_& m) {
  m.def("correct", &CorrectArrays, py::arg("parameters"), py::arg("q1"), py::arg("q2"),
        py::arg("q3"), py::arg("tau1"), py::arg("tau2"), py::arg("model") = "paper",
        py::arg("t") = py::none(), py::arg("v1") = py::none(), py::arg("v2") = py::none(),
        "Corrects joints 1-2 sample by sample (docs/correction.md).\n\n"
        "q1, q2: encoder angles (rad); q3: insertion depth (m); tau1, tau2: measured efforts "
        "(N·m); 1-D arrays of one length. model: 'paper' (equation 2, the tau_min switch) or "
        "'deadzone' (continuous). t (s), and v1, v2 (rad/s) where known: the rows as a stream, "
        "whose time, velocity and effort rate the parameters' effects read (joint friction, "
        "drift, delay), as `pliant correct` gives them; without t, no memory. Returns a dict of arrays: q1_corr, q2_corr (rad), tau1_ext, "
        "tau2_ext (N·m, tau − tau0(q)), depth_clamped (bool: q3 outside the valid depths, K(L) "
        "taken at the nearest end) — the numbers `pliant correct` writes.");
  m.def("_correct_file", &CorrectFile, py::arg("parameters"), py::arg("input"),
        py::arg("output"), py::arg("model"), py::arg("metadata_note"), py::arg("tare"),
        py::arg("skip_bad_rows"),
        "`pliant correct` on a file; see pliant.correct_log.");
}

}  // namespace pliant::python
