#pragma once
// A tare written into the parameters' bias torque itself, so that every
// consumer (pliant correct, the filter) evaluates the same tared model.
//
// The tare measures, on a log's unloaded rows r = 1..n, the mean load the
// model reads, m = mean_r(tau_r − tau0(q_r, L_r) − internal_r): the bias
// error there. Adding m to tau0 everywhere is a constant shift: every torque
// of a table, a0 of a Fourier series. For a Fourier series the tared a0 is
//   a0' = a0 + m = mean_r(tau_r − internal_r) − Σ_{k≠0} g_k·c_k,
// with g_k the mean over the rows of ∂tau0/∂c_k (cos k·q, sin k·q, L − L_ref):
// it no longer depends on the old a0, only on the other coefficients and on
// the rows' noise (σ_m). The covariance follows that linear map exactly.

#include <string>
#include <vector>

#include <Eigen/Core>

#include "pliant/models/parameters.h"

namespace pliant::estimation {

/// The angle q (rad) and depth L (m) of one joint on the tare's rows.
struct TareRows {
  std::vector<double> angle_rad;
  std::vector<double> depth_m;
};

/// σ (N·m) of the parameters' tau0 of `joint` (0 or 1) averaged over the
/// rows, from their covariance of "jointN.bias_torque.*" (first order, exact
/// for the linear Fourier form); 0 when they carry none (a table has none).
double BiasSdOver(const models::ModelParameters& parameters, int joint, const TareRows& rows);

/// Adds offset_nm to the bias torque of `joint` at every angle and depth,
/// updates the covariance of a Fourier bias as above (a0 is added to it if it
/// was not there; the noise of the tare, offset_sd_nm, is a0's own), and
/// appends `note` to the joint's sources["bias_torque"].
void TareBiasTorque(int joint, double offset_nm, double offset_sd_nm, const TareRows& rows,
                    const std::string& note, models::ModelParameters* parameters);

}  // namespace pliant::estimation
