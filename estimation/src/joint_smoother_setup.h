#pragma once
// Initial values and priors of the joint smoother (joint_smoother.cpp solves).

#include <array>
#include <map>
#include <vector>

#include "identification_common.h"
#include "pliant/estimation/identification.h"
#include "pliant/estimation/joint_smoother.h"

namespace pliant::estimation::detail {

/// Every unknown of the smoother, in the memory Ceres works on.
struct SmootherState {
  std::array<std::array<double, 4>, 2> law{};
  std::array<double, 2> delta_rad{}, log_width{};
  std::array<std::vector<double>, 2> bias;  ///< a0, a1, b1, …, depth slope, c1, d1
  std::map<int, std::array<double, 2>> tip_rad;  ///< per tip_fixed segment
  std::vector<std::array<double, 2>> tau_ext_nm;  ///< per sample
};

/// Noise of one log row, per joint and per kind of sample (free / tip_fixed):
/// the fit rescales them to the residuals it finds.
struct SmootherNoise {
  std::array<double, 2> effort_free_nm{}, effort_fixed_nm{}, angle_fixed_rad{};
};

/// Prior means and standard deviations of the global unknowns.
struct SmootherPrior {
  std::array<std::array<double, 4>, 2> law{}, law_sd{};
  std::array<double, 2> delta_rad{}, delta_sd{}, log_width{}, log_width_sd{};
  std::array<std::vector<double>, 2> bias, bias_sd;
};

/// The chosen law fitted to the prior's K(L) over the prior's depth range.
models::ComplianceLaw ConvertLaw(const models::JointParameters& joint, models::ComplianceForm form,
                                 double cannula_length_m);

SmootherPrior MakePrior(const models::ModelParameters& prior, const JointSmootherOptions& options);

/// Starting point: the paper's procedure where it has data, the prior elsewhere;
/// bias by linear least squares on the free-tip samples.
SmootherState MakeInitialState(const IdentificationData& data, const SmootherPrior& prior,
                               const IdentificationResult& paper,
                               const JointSmootherOptions& options,
                               const UndeterminedParameters& held);

/// Holds each of joint j's depth-harmonic coefficients (c1, d1) at its prior
/// unless the free-tip rows determine it: its posterior sd from them (every
/// other bias coefficient free, the rows at the starting effort noise) below
/// `identified_fraction` of its prior sd. One sweep depth cannot tell
/// (L − L_ref)·c1 from a1; sweeps at two depths that span the joint angle can;
/// sweeps of a few degrees about q = 0 fix d1 (the depth's change of τ0's
/// slope) but not c1 (cos q ≈ 1: the depth slope s).
void HoldUndeterminedDepthHarmonic(const IdentificationData& data, const SmootherPrior& prior,
                                   const JointSmootherOptions& options,
                                   UndeterminedParameters* held);

/// tau0 of joint j from the state's bias coefficients.
double BiasOf(const SmootherState& state, int joint, const IdentificationSample& sample,
              const JointSmootherOptions& options);

}  // namespace pliant::estimation::detail
