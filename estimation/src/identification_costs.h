#pragma once
// The smoother's residuals, built on the models/ effects. All automatic
// differentiation of identification lives in identification_costs.cpp, so
// that only one translation unit pays Ceres' template compile time.

#include <array>

#include <ceres/cost_function.h>

#include "pliant/estimation/identification_data.h"
#include "pliant/models/parameters.h"

namespace pliant::estimation::detail {

/// Largest Fourier harmonic count the residuals accept.
inline constexpr int kMaxBiasHarmonics = 6;

/// (tau_meas_j − tau0_j(q, L) − tau_ext_j) / sd. Parameter blocks: the joint's
/// bias coefficients (2·harmonics + 2: a0, a1, b1, …, depth slope), then, when
/// `latent_torque`, tau_ext_j (1).
ceres::CostFunction* NewEffortResidual(const IdentificationSample& sample, int joint,
                                       int harmonics, double reference_depth_m, double sd_nm,
                                       bool latent_torque);

/// (q_j − tip_j − [delta_j·S(tau_ext_j / w_j) + K_j(L)·tau_ext_j]) / sd.
/// Parameter blocks: tau_ext_j (1), tip_j (1), law_j / law_scale (4), delta_j (1),
/// log w_j (1). The law's numbers are scaled (by their prior sd) so that every
/// column of the Jacobian has a comparable norm: a cubic's c3 and c0 differ by
/// three orders of magnitude, and QR would call the small one rank-deficient.
/// `law_forms` gives both joints' forms; the other joint's law is never used.
ceres::CostFunction* NewAngleResidual(const IdentificationSample& sample, int joint,
                                      const std::array<models::ComplianceForm, 2>& law_forms,
                                      const std::array<double, 4>& law_scale, double sd_rad);

/// Evaluates the same angle model with doubles: the deflection (rad) of joint
/// j at load tau (N·m) and depth L for given law, delta and log width.
double Deflection(int joint, const std::array<models::ComplianceForm, 2>& law_forms,
                  const double* law, double delta_rad, double log_width, double tau_nm,
                  double depth_m);

/// The quasi-static clamped-beam angle with the held-friction effect
/// (models/effects/held_friction.h), for one recorded joint:
///   (q_j − tip − K_j(L)·tau_e − δ_j·S(tau_e / w_j)) / sd,
///   tau_e = tau_meas_j − tau0_j − held_friction_j(travel; F_j, λ),
/// K and the dead zone δ·S the compliance and backlash effects', as the
/// smoother's. Parameter blocks: tip (1), law / law_scale (4), F_j (1), δ_j
/// (1), log w_j (1, N·m). λ is held.
ceres::CostFunction* NewHeldFrictionAngleResidual(const IdentificationSample& sample, int joint,
                                                  models::ComplianceForm form,
                                                  const std::array<double, 4>& law_scale,
                                                  double bias_nm, double presliding_travel_rad,
                                                  double sd_rad);

}  // namespace pliant::estimation::detail
