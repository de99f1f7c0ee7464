#pragma once
// The effect: pliant's one extension point.
//
// A physical effect (bias torque, shaft compliance, cannula backlash, friction,
// drift, ...) is written once, as a small type whose contribution is a function
// templated on the scalar type T. The same code then serves
//   - the simulator, with T = double,
//   - the online filter and the Ceres smoother, with T = ceres::Jet (exact
//     Jacobians by automatic differentiation).
//
// The model of PSM joints 1 (yaw) and 2 (pitch) has two places an effect can act:
//
//   measured effort      tau_meas = sum of kInternalTorque effects + tau_ext
//   encoder angle        q_enc    = q_tip + sum of kDeflection effects
//
// where tau_ext is the external torque (N·m) the environment applies through the
// instrument and q_tip is the tip-consistent ("corrected") joint angle (rad).
// Internal-torque effects see the joint state; deflection effects also see
// tau_ext = tau_meas - internal torque.
//
// A complete user-defined effect (a joint-1 deflection proportional to the
// pitch torque, i.e. coupling between the two lateral directions):
//
//   struct CrossCoupling {
//     static constexpr pliant::models::EffectInfo kInfo{
//         "cross_coupling", pliant::models::Channel::kDeflection,
//         "the shaft bends a little toward yaw when pushed in pitch"};
//     std::vector<pliant::models::ParameterSpec> Parameters() const {
//       return {{"k12", "rad/(N·m)", 0.0, -0.05, 0.05, 0.01}};
//     }
//     template <typename T>
//     pliant::models::Vec2<T> operator()(const T* p,
//                                        const pliant::models::JointState<T>& s) const {
//       return {p[0] * s.external_torque_nm[1], T(0.0)};
//     }
//   };
//
// Register it with pliant::estimation::EffectCatalogue::Global().Add<CrossCoupling>()
// and check its derivatives with pliant::estimation::CheckEffectJacobians (see
// estimation/effect_catalogue.h and estimation/jacobian_check.h). Write the body
// with operations that exist for ceres::Jet: arithmetic, comparisons against
// values, and the functions of <cmath> called unqualified (using std::tanh;).

#include <Eigen/Core>
#include <string>
#include <string_view>
#include <vector>

namespace pliant::models {

/// Two joint values: index 0 is joint 1 (yaw), index 1 is joint 2 (pitch).
template <typename T>
using Vec2 = Eigen::Matrix<T, 2, 1>;

/// Where an effect's contribution enters the joint model (see the header comment).
enum class Channel {
  kInternalTorque,  ///< N·m added to the measured effort of each joint
  kDeflection,      ///< rad added to the encoder angle beyond the tip angle
};

/// One named parameter of an effect. Bounds and prior are what an estimator
/// uses; the default is the value a simulator uses when a scenario is silent.
struct ParameterSpec {
  std::string name;  ///< e.g. "delta1"
  std::string unit;  ///< e.g. "rad", "N·m", "rad/(N·m)"
  double default_value;
  double lower_bound;
  double upper_bound;
  double prior_sd;         ///< standard deviation of the Gaussian prior, same unit
};

/// What an effect is, in one line a person can act on.
struct EffectInfo {
  std::string_view name;         ///< catalogue key, snake_case
  Channel channel;
  std::string_view explanation;  ///< the physics, in one sentence
};

/// What an effect sees of the two joints at one sample.
template <typename T>
struct JointState {
  Vec2<T> encoder_angle_rad = Vec2<T>::Zero();   ///< q1, q2 (motor encoders)
  T insertion_depth_m = T(0.0);                  ///< q3: RCM to instrument, m
  Vec2<T> external_torque_nm = Vec2<T>::Zero();  ///< tau_ext (deflection effects only)
  Vec2<T> velocity_rad_s = Vec2<T>::Zero();      ///< v1, v2
  T time_s = T(0.0);                             ///< log time, s
  Vec2<T> effort_rate_nm_s = Vec2<T>::Zero();    ///< d tau_meas / dt (the effort-delay effect)
  /// Signed encoder travel since the joint last reversed (rad; the held-friction
  /// effect): models::TravelSinceReversal computes it from the rows so far.
  Vec2<T> travel_since_reversal_rad = Vec2<T>::Zero();
  /// d v / dt (rad/s²; the arm's inertia): the velocity's rate over the same
  /// window as the effort's (estimation::EffectInputs), 0 on a pose log.
  Vec2<T> acceleration_rad_s2 = Vec2<T>::Zero();
  /// K_j(L): the compliance law of the model the effect extends, at this
  /// depth (rad/(N·m); deflection effects only). A shaft's stiffening with
  /// the load is a share of its bend at that depth, so it scales with it.
  Vec2<T> compliance_rad_per_nm = Vec2<T>::Zero();

  /// The same state in another scalar type (e.g. double -> ceres::Jet).
  template <typename U>
  JointState<U> Cast() const {
    JointState<U> out;
    out.encoder_angle_rad = encoder_angle_rad.template cast<U>();
    out.insertion_depth_m = U(insertion_depth_m);
    out.external_torque_nm = external_torque_nm.template cast<U>();
    out.velocity_rad_s = velocity_rad_s.template cast<U>();
    out.time_s = U(time_s);
    out.effort_rate_nm_s = effort_rate_nm_s.template cast<U>();
    out.travel_since_reversal_rad = travel_since_reversal_rad.template cast<U>();
    out.acceleration_rad_s2 = acceleration_rad_s2.template cast<U>();
    out.compliance_rad_per_nm = compliance_rad_per_nm.template cast<U>();
    return out;
  }
};

/// Number of scalar inputs in a JointState, in the order
/// q1, q2, q3, tau_ext1, tau_ext2, v1, v2, t, tau_rate1, tau_rate2, travel1,
/// travel2, a1, a2, K1, K2 (used by the Jacobian check).
inline constexpr int kJointStateSize = 16;

}  // namespace pliant::models
