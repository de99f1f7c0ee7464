#pragma once
// The shaft's own damping: a shaft bearing on a cannula wall resists being
// bent, c_s·d' on top of its elastic load, where d' is how fast the motor side
// turns against the tip (with the tip held, the motor's velocity). Inside the
// clearance it touches nothing and takes nothing. The motor's effort carries
// this torque, the deflection does not: read as load, it becomes K·c_s·d' of
// deflection that is not there.
//
// One formula for the simulator (hold 0 or 1: in contact or not; d' its own
// state) and the filter (hold g = BacklashHold of the load it is sure of; d'
// the motor's fitted velocity while the tip is held).

namespace pliant::models {

/// c_s·hold·d' (N·m), for damping c_s (N·m·s/rad, >= 0), bend rate d' (rad/s)
/// and hold ∈ [0, 1], how firmly the shaft bears on a wall.
template <typename T, typename Hold>
T ShaftDampingTorque(double damping_nm_s_per_rad, const T& bend_rate_rad_s, const Hold& hold) {
  return damping_nm_s_per_rad * hold * bend_rate_rad_s;
}

}  // namespace pliant::models
