#pragma once
// Identification from quasi-static logs that record one joint each (the JHU
// 2017 bias sweeps and clamped beams, docs/real-data.md). Per recorded joint:
//
//  - the bias table tau0(q_j): free-tip effort averaged per 5° of q_j (the
//    paper's, over both directions of motion, so that the held friction
//    averages out);
//  - on the clamped rows, one Ceres problem: a tip angle per clamp (segment),
//    the compliance law K_j(L), the held friction F_j (effects/held_friction.h,
//    presliding travel λ held) and the clearance δ_j ≥ 0:
//      q_j = tip_s + K_j(L)·tau_e + δ_j·sgn(tau_e),
//      tau_e = tau_j − tau0_j(q_j) − F_j·z(travel since reversal);
//  - the covariance by the clustered sandwich over clamps (docs/decisions/
//    0001-identification-sigma-by-depth-clusters.md): residuals within one
//    depth are correlated (the unknown start, the model's error), so each
//    depth counts as one independent block, not each row.
//
// A joint no log records keeps its prior (the result's warnings say so).

#include <vector>

#include "pliant/estimation/identification.h"

namespace pliant::estimation {

struct QuasiStaticOptions {
  bool held_friction = true;             ///< fit F_j (otherwise the paper's form)
  double presliding_travel_rad = 0.002;  ///< λ of the held friction
  double bias_table_step_rad = 5.0 * 3.14159265358979323846 / 180.0;
  /// A depth whose fit RMS exceeds this many times the median depth's is
  /// reported in words as a misfit.
  double misfit_factor = 1.5;
};

/// Throws std::invalid_argument when no joint has clamped rows at ≥ 5 depths
/// (the law has 4 numbers).
IdentificationResult RunQuasiStaticIdentification(const IdentificationData& data,
                                                  const models::ModelParameters& prior,
                                                  const QuasiStaticOptions& options = {});

/// Per clamp (segment) of joint j: the straight-line slope 1/K of the paper's
/// Fig. 6 with tau_e as above (F_j, δ_j and tau0 given), and the RMS of the
/// line's residual. Used for the report and the cross-validation check.
std::vector<DepthEstimate> PerDepthSlopes(const IdentificationData& data,
                                          const models::ModelParameters& parameters, int joint,
                                          double presliding_travel_rad);

}  // namespace pliant::estimation
