#pragma once
// A hand-made log and Diagnosis for the report tests: joint 1 reads 1 mrad
// high while v1 > 0 (friction the model lacks); with joint_friction added the
// residual is a tenth of that.
#include <cmath>
#include <string>

#include "pliant/estimation/diagnosis.h"
#include "pliant/io/log.h"

namespace pliant::testing {

inline io::Log ExampleLog(std::size_t rows = 400) {
  io::Log log;
  log.header.columns = {"t", "q1", "q2", "q3", "tau1", "tau2", "v1", "v2", "segment"};
  for (std::size_t i = 0; i < rows; ++i) {
    const double t = 0.02 * i, v1 = std::sin(t), v2 = std::cos(0.7 * t);
    log.values.insert(log.values.end(), {t, 0.1 * std::sin(t), 0.05, 0.12, 0.2 * std::cos(t),
                                         0.1 * v2, v1, v2, double(1 + i / 100)});
  }
  return log;
}

inline estimation::Diagnosis ExampleDiagnosis(const io::Log& log) {
  estimation::Diagnosis d;
  d.reference = "tip_fixed";
  d.rms_before_mm = 1.234;
  d.rms_after_mm = 0.123;
  d.missing_effect = "joint_friction";
  d.before.samples = d.after.samples = log.Rows();
  d.before.rms_rad[0] = 1.0e-3;
  d.after.rms_rad[0] = 0.1e-3;
  d.before.mean_nis = 9.5;
  d.after.mean_nis = 1.02;
  d.before.ljung_box_p = 1e-12;
  d.after.ljung_box_p = 0.41;
  estimation::EffectFinding friction;
  friction.name = "joint_friction";
  friction.description = "viscous <and> Coulomb friction";
  friction.channels = {"v1", "v2"};
  friction.score = 0.9;
  friction.p_value = 1e-9;
  friction.delta_aic = -512.5;
  friction.heldout_rms_before_mm = 1.234;
  friction.heldout_rms_after_mm = 0.123;
  friction.size = 0.87;
  friction.size_sd = 0.02;
  friction.size_unit = "mm";
  friction.parameter_names = {"coulomb1", "viscous1"};
  friction.parameters = {0.05, 0.001};
  friction.parameter_sd = {0.002, 0.0004};
  friction.missing = true;
  estimation::EffectFinding drift;
  drift.name = "effort_drift";
  drift.description = "the effort offset creeps";
  drift.channels = {"t"};
  drift.score = 0.05;
  drift.p_value = 0.6;
  drift.size = 0.1;
  drift.size_sd = 0.08;
  drift.size_unit = "mm";
  d.effects = {friction, drift};
  d.channels = {{"sign(v1)", 1, 0, 0.81, 1e-20, "joint 1 reads 1 mrad high while v1 > 0", ""},
                {"|tau1|", 1, 2, 0.12, 1e-3, "grows with the load", ""},
                {"t", 2, 0, 0.01, 0.9, "", ""}};
  for (std::size_t i = 0; i < log.Rows(); ++i) {
    const double v1 = log.Value(i, 6);
    d.series.row.push_back(i);
    d.series.residual_before_rad[0].push_back(v1 > 0 ? 1e-3 : -1e-3);
    d.series.residual_before_rad[1].push_back(0.1e-3 * std::sin(0.3 * i));
    d.series.residual_after_rad[0].push_back(0.1e-3 * std::sin(1.3 * i));
    d.series.residual_after_rad[1].push_back(0.1e-3 * std::sin(0.3 * i));
    d.series.standardised_innovation.push_back(std::sin(2.1 * i));
  }
  return d;
}

}  // namespace pliant::testing
