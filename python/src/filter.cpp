// The online filter (docs/filter.md) for a control loop — pliant.Filter, one
// sample per step() — and over a whole log file through
// estimation::FilterLog, the function `pliant filter` runs. The filter's C++
// API may change; this file and filter_options.cpp are the only ones that
// know it.
#include <cmath>
#include <string>

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "bindings.h"
#include "filter_options.h"
#include "pliant/estimation/filter_log.h"
#include "pliant/io/input_error.h"

namespace pliant::python {
namespace {

using estimation::ComplianceFilter;
using estimation::FilterEstimate;
using estimation::FilterSample;
using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

FilterSample Sample(double t, double q1, double q2, double q3, double tau1, double tau2,
                    double q1_ref, double q2_ref, bool tip_fixed) {
  FilterSample s;
  s.time_s = t;
  s.encoder_rad = {q1, q2};
  s.insertion_depth_m = q3;
  s.effort_nm = {tau1, tau2};
  s.reference_rad = {q1_ref, q2_ref};
  s.tip_fixed = tip_fixed;
  return s;
}

FilterSample SampleFromArray(const Array& a) {
  if (a.ndim() != 1 || a.size() < 6 || a.size() > 9) {
    throw io::InputError("sample", 0, 0,
                         "holds " + std::to_string(a.size()) + " values in " +
                             std::to_string(a.ndim()) + " dimension(s)",
                         "give (t, q1, q2, q3, tau1, tau2[, q1_ref, q2_ref[, tip_fixed]]) in "
                         "s, rad, rad, m, N·m, N·m, rad, rad");
  }
  const double nan = FilterSample::kMissing;
  const auto n = a.size();
  return Sample(a.at(0), a.at(1), a.at(2), a.at(3), a.at(4), a.at(5), n > 6 ? a.at(6) : nan,
                n > 7 ? a.at(7) : nan, n > 8 && a.at(8) >= 0.5);
}

py::dict FilterFile(Parameters parameters, const std::string& input, const std::string& output,
                    bool smooth, const py::dict& options, std::string metadata_note,
                    const std::string& tare, bool skip_bad_rows) {
  const auto filter_options = FilterOptionsFrom(options);
  const std::string tared = TareForLog(input, tare, &parameters, &metadata_note);
  estimation::LogFilterSummary s;
  {
    py::gil_scoped_release unlocked;
    s = estimation::FilterLog(input, output, parameters, filter_options, smooth, metadata_note,
                              {skip_bad_rows});
  }
  py::dict out;
  out["rows"] = s.rows, out["skipped_rows"] = s.skipped_rows;
  out["rejected_rows"] = s.rejected_rows, out["missing_rows"] = s.missing_rows;
  out["depth_out_of_range_rows"] = s.depth_out_of_range_rows;
  out["saturated_rows"] = s.saturated_rows, out["mismatch_rows"] = s.mismatch_rows;
  out["smoothed"] = s.smoothed, out["reference"] = s.reference;
  out["mean_nis_per_dof"] = s.mean_nis_per_dof;
  out["notes"] = s.notes, out["advice"] = s.advice;
  out["uncorrected"] = TipErrorDict(s.uncorrected);
  out["filtered"] = TipErrorDict(s.filtered);
  if (s.smoothed) out["smoothed_error"] = TipErrorDict(s.smoothed_error);
  out["tare"] = tared;
  return out;
}

void BindEstimate(py::module_& m) {
  py::class_<FilterEstimate>(m, "FilterEstimate", "One step's output of pliant.Filter.")
      .def_readonly("corrected", &FilterEstimate::corrected_rad,
                    "q̂1, q̂2 (rad): the corrected joint angles, moved at most "
                    "output_step_limit_counts beyond the encoder's change per step.")
      .def_readonly("covariance", &FilterEstimate::covariance_rad2,
                    "2×2 mean squared error of `corrected` (rad²).")
      .def_property_readonly(
          "sd",
          [](const FilterEstimate& e) {
            return Eigen::Vector2d(e.covariance_rad2.diagonal().cwiseSqrt());
          },
          "q1_sd, q2_sd (rad): square roots of the covariance's diagonal.")
      .def_readonly("filtered", &FilterEstimate::filtered_rad,
                    "The filter's mean of the tip angles (rad), before the output step limit.")
      .def_readonly("tip_correction_mm", &FilterEstimate::tip_correction_mm,
                    "|uncorrected tip − corrected tip| through the PSM kinematics (mm).")
      .def_readonly("tip_correction_sd_mm", &FilterEstimate::tip_correction_sd_mm,
                    "Its standard deviation (mm).")
      .def_readonly("nis", &FilterEstimate::nis, "Normalised innovation squared of the step.")
      .def_readonly("nis_dof", &FilterEstimate::nis_dof, "Scalar measurements the NIS sums.")
      .def_readonly("flags", &FilterEstimate::flags, "FLAG_* bits (pliant.FLAG_REJECTED, …).")
      .def_readonly("contact_probability", &FilterEstimate::contact_probability,
                    "The probability that something touches the instrument, per joint (1 with "
                    "the tip_fixed hint).")
      .def_readonly("external_torque_nm", &FilterEstimate::external_torque_nm,
                    "Estimated external torques on joints 1-2 (N·m).")
      .def_readonly("backlash_offset_rad", &FilterEstimate::backlash_offset_rad,
                    "Where each shaft sits in its clearance (rad).")
      .def_readonly("compliance_scale", &FilterEstimate::compliance_scale,
                    "s: the shaft's compliance is s·K(L) (1 = the parameters').")
      .def_readonly("clearance_error_rad", &FilterEstimate::clearance_error_rad,
                    "Clearance minus the parameters' δ (rad).")
      .def_readonly("effort_offset_nm", &FilterEstimate::effort_offset_nm,
                    "β: a constant offset the bias torque misses (N·m).");
  m.attr("FLAG_REJECTED") = static_cast<unsigned>(estimation::kFlagRejected);
  m.attr("FLAG_MISSING") = static_cast<unsigned>(estimation::kFlagMissing);
  m.attr("FLAG_DEPTH_OUT_OF_RANGE") = static_cast<unsigned>(estimation::kFlagDepthOutOfRange);
  m.attr("FLAG_EFFORT_SATURATED") = static_cast<unsigned>(estimation::kFlagEffortSaturated);
  m.attr("FLAG_MODEL_MISMATCH") = static_cast<unsigned>(estimation::kFlagModelMismatch);
  m.attr("FLAG_REACQUIRED") = static_cast<unsigned>(estimation::kFlagReacquired);
  m.attr("FLAG_REPAIRED") = static_cast<unsigned>(estimation::kFlagRepaired);
  m.attr("FLAG_OUTPUT_LIMITED") = static_cast<unsigned>(estimation::kFlagOutputLimited);
}

}  // namespace

void BindFilter(py::module_& m) {
  BindEstimate(m);
  const double nan = FilterSample::kMissing;
  py::class_<ComplianceFilter>(
      m, "Filter",
      "The online EKF of joints 1-2 (docs/filter.md), one sample per step(), for a control "
      "loop: never allocates in C++, and the first step initialises it.\n\n"
      "Filter(parameters, **options): options are FilterOptions fields "
      "(pliant.filter_option_defaults() lists them, with units in their names); raises "
      "InputError for an unknown or invalid one.")
      .def(py::init([](const Parameters& p, const py::kwargs& options) {
             return ComplianceFilter(p, FilterOptionsFrom(options));
           }),
           py::arg("parameters"))
      .def(
          "step",
          [](ComplianceFilter& f, double t, double q1, double q2, double q3, double tau1,
             double tau2, double q1_ref, double q2_ref, bool tip_fixed) {
            return f.Step(Sample(t, q1, q2, q3, tau1, tau2, q1_ref, q2_ref, tip_fixed));
          },
          py::arg("t"), py::arg("q1"), py::arg("q2"), py::arg("q3"), py::arg("tau1"),
          py::arg("tau2"), py::arg("q1_ref") = nan, py::arg("q2_ref") = nan,
          py::arg("tip_fixed") = false,
          "Advances one control period. t (s), q1, q2 (rad, encoders), q3 (m, insertion "
          "depth), tau1, tau2 (N·m, measured efforts); q1_ref, q2_ref (rad, an external "
          "reference, NaN when absent); tip_fixed (the tip is clamped or in a divot). NaN "
          "marks a missing value. Returns a FilterEstimate (corrected, covariance, …).")
      .def(
          "step",
          [](ComplianceFilter& f, const Array& sample) { return f.Step(SampleFromArray(sample)); },
          py::arg("sample"),
          "Advances one control period from a sequence (t, q1, q2, q3, tau1, tau2[, q1_ref, "
          "q2_ref[, tip_fixed]]) in s, rad, rad, m, N·m, N·m, rad, rad, 0/1.")
      .def("reset", &ComplianceFilter::Reset, "Back to the prior; the next step initialises.");
  m.def("filter_option_defaults", &FilterOptionDefaults,
        "The filter options pliant.Filter and pliant.filter_log take, with their defaults "
        "(units in the names; NaN: chosen from the parameters or other options).");
  m.def("_filter_file", &FilterFile, py::arg("parameters"), py::arg("input"), py::arg("output"),
        py::arg("smooth"), py::arg("options"), py::arg("metadata_note"), py::arg("tare"),
        py::arg("skip_bad_rows"), "`pliant filter` on a file; see pliant.filter_log.");
}

}  // namespace pliant::python
