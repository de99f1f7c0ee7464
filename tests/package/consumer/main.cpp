// An outside project: the paper's correction of one sample, by the installed pliant.
#include <cmath>
#include <cstdio>

#include "pliant/estimation/compliance_correction.h"

int main() {
  pliant::models::ModelParameters p;
  for (auto& joint : p.joints) {
    joint.bias_torque = {{0.0}, {0.0}};
    joint.compliance.cubic.coefficients = {0.0, 0.0, 0.0, 20.0};  // K = 0.05 rad/(N·m)
    joint.backlash_rad = 0.008;
    joint.tau_min_nm = 0.1;
    joint.deadzone_width_nm = 0.1;
    joint.depth_min_m = 0.09;
    joint.depth_max_m = 0.22;
  }
  const pliant::estimation::ComplianceCorrector corrector(
      p, pliant::estimation::CorrectionModel::kPaper);
  const auto c = corrector.Correct({0.1, 0.2, 0.15}, {1.0, -0.5});
  // q1: 0.1 − (0.008 + 0.05·1.0) = 0.042;  q2: 0.2 − (−0.008 − 0.025) = 0.233
  const bool ok = std::abs(c.corrected_rad[0] - 0.042) < 1e-12 &&
                  std::abs(c.corrected_rad[1] - 0.233) < 1e-12;
  std::printf("consumer: q1_corr %.6f q2_corr %.6f %s\n", c.corrected_rad[0], c.corrected_rad[1],
              ok ? "ok" : "WRONG");
  return ok ? 0 : 1;
}
