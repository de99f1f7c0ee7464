#pragma once
// Bias torque tau0(q): the effort the PID controller spends, with no external
// load, against the counterbalance and gravity (paper, section 2 and Fig. 4).

#include <string>
#include <vector>

#include "pliant/models/effect.h"
#include "pliant/models/parameters.h"

namespace pliant::models {

/// Each joint's bias torque is a table over its own angle; the table values
/// (N·m) are the parameters, joint 1's first. The angles are configuration.
class BiasTorqueEffect {
 public:
  static constexpr EffectInfo kInfo{
      "bias_torque", Channel::kInternalTorque,
      "effort spent against counterbalance and gravity, a function of the joint angle"};

  /// A flat table (one knot at 0 rad) per joint: the catalogue's default.
  BiasTorqueEffect();
  BiasTorqueEffect(const BiasTorqueTable& joint1, const BiasTorqueTable& joint2);

  std::vector<ParameterSpec> Parameters() const;

  template <typename T>
  Vec2<T> operator()(const T* torque_nm, const JointState<T>& state) const {
    const std::size_t n1 = angles_[0].size();
    return {Interpolate(angles_[0], torque_nm, state.encoder_angle_rad[0]),
            Interpolate(angles_[1], torque_nm + n1, state.encoder_angle_rad[1])};
  }

 private:
  // Linear interpolation, constant beyond the ends (the calibration does not
  // say what happens outside the range it swept).
  template <typename T>
  static T Interpolate(const std::vector<double>& angles, const T* values, const T& q) {
    const std::size_t n = angles.size();
    if (n == 1 || q <= angles.front()) return values[0];
    if (q >= angles.back()) return values[n - 1];
    std::size_t i = 1;
    while (q > angles[i]) ++i;
    const T w = (q - angles[i - 1]) / (angles[i] - angles[i - 1]);
    return values[i - 1] + w * (values[i] - values[i - 1]);
  }

  std::vector<double> angles_[2];
  std::vector<double> defaults_;
};

}  // namespace pliant::models
