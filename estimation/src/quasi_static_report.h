#pragma once
// The words and figures of the quasi-static identification: per-depth slopes,
// where the model does not fit (which depth, which branch, how many mrad),
// the clearance at its bound, and the depth-to-depth scatter the σ carry.

#include <Eigen/Core>

#include "pliant/estimation/identification_quasi_static.h"

namespace pliant::estimation::detail {

/// Fills result->depth_estimates for joint j, appends warnings in words, adds
/// the per-depth slopes and reports the white-noise
/// against the clustered σ. Returns the scatter's sd (N·m/rad).
double DescribeMisfit(const IdentificationData& data, models::ModelParameters& parameters,
                    const models::EffectParameters& friction, int joint,
                    const QuasiStaticOptions& options, const Eigen::MatrixXd& white,
                    const Eigen::MatrixXd& sandwich, IdentificationResult* result);

}  // namespace pliant::estimation::detail
