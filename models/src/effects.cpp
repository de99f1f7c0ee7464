// Parameter lists of the built-in effects: names, units, defaults, bounds, priors.
#include <string>

#include "pliant/models/effects/backlash.h"
#include "pliant/models/effects/bias_torque.h"
#include "pliant/models/effects/bias_torque_fourier.h"
#include "pliant/models/effects/compliance.h"
#include "pliant/models/paper_parameters.h"

namespace pliant::models {
namespace {

std::string JointName(int j) { return std::to_string(j + 1); }

}  // namespace

BiasTorqueEffect::BiasTorqueEffect() : BiasTorqueEffect({{0.0}, {0.0}}, {{0.0}, {0.0}}) {}

BiasTorqueEffect::BiasTorqueEffect(const BiasTorqueTable& joint1, const BiasTorqueTable& joint2) {
  angles_[0] = joint1.angle_rad;
  angles_[1] = joint2.angle_rad;
  defaults_ = joint1.torque_nm;
  defaults_.insert(defaults_.end(), joint2.torque_nm.begin(), joint2.torque_nm.end());
}

std::vector<ParameterSpec> BiasTorqueEffect::Parameters() const {
  std::vector<ParameterSpec> specs;
  std::size_t k = 0;
  for (int j = 0; j < 2; ++j) {
    for (std::size_t i = 0; i < angles_[j].size(); ++i, ++k) {
      // Prior: the dVRK effort limit bounds any plausible bias; 0.2 N·m is the
      // spread of the paper's Fig. 4 across the range.
      specs.push_back({"tau0_" + JointName(j) + "[" + std::to_string(i) + "]", "N·m",
                       defaults_[k], -3.316, 3.316, 0.2});
    }
  }
  return specs;
}

ComplianceEffect::ComplianceEffect()
    : ComplianceEffect(PaperParameters().joints[0], PaperParameters().joints[1]) {}

ComplianceEffect::ComplianceEffect(const JointParameters& joint1, const JointParameters& joint2) {
  const JointParameters* joints[2] = {&joint1, &joint2};
  for (int j = 0; j < 2; ++j) {
    forms_[j] = joints[j]->compliance.form;
    depth_min_m_[j] = joints[j]->depth_min_m;
    depth_max_m_[j] = joints[j]->depth_max_m;
    for (double c : joints[j]->compliance.cubic.coefficients) defaults_.push_back(c);
  }
}

std::vector<ParameterSpec> ComplianceEffect::Parameters() const {
  std::vector<ParameterSpec> specs;
  static const char* kPowers[4] = {"3", "2", "1", "0"};
  for (int j = 0; j < 2; ++j) {
    if (forms_[j] == ComplianceForm::kBeamSeries) {
      // Priors: the paper's K is 0.03–0.08 rad/(N·m); an 8 mm steel tube has
      // 1/(EI) ≈ 0.05 /(N·m²); the cannula tip sits 25 mm beyond the RCM.
      const double* d = &defaults_[4 * j];
      const std::string k = "k" + JointName(j);
      specs.push_back({k + "_joint", "rad/(N·m)", d[0], 0.0, 1.0, 0.05});
      specs.push_back({k + "_structure", "rad/N", d[1], 0.0, 0.1, 0.005});
      specs.push_back({k + "_shaft_flexibility", "1/(N·m²)", d[2], 0.0, 100.0, 1.0});
      specs.push_back({k + "_cannula_length", "m", d[3], 0.0, 0.1, 0.005});
      continue;
    }
    const bool inverse = forms_[j] == ComplianceForm::kInverseCubic;
    for (int i = 0; i < 4; ++i) {
      const double value = defaults_[4 * j + i];
      std::string unit = inverse ? "N·m/rad/m^" : "rad/(N·m)/m^";
      unit += kPowers[i];
      // A cubic fit's coefficients are strongly correlated; the prior is wide
      // (half the value, at least 1 unit) and the bounds are open.
      const double sd = std::max(0.5 * std::abs(value), 1.0);
      specs.push_back({std::string(inverse ? "inv_k" : "k") + JointName(j) + "_c" + kPowers[i],
                       unit, value, -1e6, 1e6, sd});
    }
  }
  return specs;
}

BiasTorqueFourierEffect::BiasTorqueFourierEffect(int harmonics, double reference_depth_m)
    : harmonics_(harmonics), reference_depth_m_(reference_depth_m) {}

std::vector<ParameterSpec> BiasTorqueFourierEffect::Parameters() const {
  // Prior: the counterbalance leaves a few tenths of a N·m (paper Fig. 4);
  // the depth slope of the dVRK file is −0.24 N·m/m; the gravity moment's
  // arm grows with depth by the instrument's weight, a few N·m per m at most.
  std::vector<ParameterSpec> specs;
  for (int j = 0; j < 2; ++j) {
    const std::string joint = JointName(j);
    specs.push_back({"tau0_" + joint + "_a0", "N·m", 0.0, -3.316, 3.316, 0.5});
    for (int k = 1; k <= harmonics_; ++k) {
      specs.push_back({"tau0_" + joint + "_a" + std::to_string(k), "N·m", 0.0, -3.316, 3.316, 0.5});
      specs.push_back({"tau0_" + joint + "_b" + std::to_string(k), "N·m", 0.0, -3.316, 3.316, 0.5});
    }
    specs.push_back({"tau0_" + joint + "_depth_slope", "N·m/m", 0.0, -10.0, 10.0, 1.0});
    specs.push_back({"tau0_" + joint + "_depth_c1", "N·m/m", 0.0, -10.0, 10.0, 1.0});
    specs.push_back({"tau0_" + joint + "_depth_d1", "N·m/m", 0.0, -10.0, 10.0, 1.0});
  }
  return specs;
}

BacklashSignEffect::BacklashSignEffect(double delta1_rad, double delta2_rad)
    : delta_rad_{delta1_rad, delta2_rad} {}

std::vector<ParameterSpec> BacklashSignEffect::Parameters() const {
  // Prior sd 0.004 rad: the dVRK file's values are 0.007–0.008 rad and the
  // clearance of an 8 mm instrument in its cannula is of that order.
  return {{"delta1", "rad", delta_rad_[0], 0.0, 0.05, 0.004},
          {"delta2", "rad", delta_rad_[1], 0.0, 0.05, 0.004}};
}

BacklashDeadZoneEffect::BacklashDeadZoneEffect(double delta1_rad, double delta2_rad,
                                               double width1_nm, double width2_nm)
    : defaults_{delta1_rad, delta2_rad, width1_nm, width2_nm} {}

std::vector<ParameterSpec> BacklashDeadZoneEffect::Parameters() const {
  return {{"delta1", "rad", defaults_[0], 0.0, 0.05, 0.004},
          {"delta2", "rad", defaults_[1], 0.0, 0.05, 0.004},
          {"width1", "N·m", defaults_[2], 1e-3, 1.0, 0.1},
          {"width2", "N·m", defaults_[3], 1e-3, 1.0, 0.1}};
}

}  // namespace pliant::models
