#pragma once
// Offline identification of the compliance model of PSM joints 1 and 2 from
// logs (docs/identification.md). Two methods, one result type:
//
//  - the paper's procedure (sections 3 and 5), reproduced exactly: the bias
//    table tau0(q) from free-tip rows; per depth, a line through effort
//    against position on each branch, whose slope is 1/K at that depth; a
//    cubic in L through those; the backlash from the distance between the
//    branch lines. In equation (1) δ is HALF that distance: the shaft crosses
//    the whole clearance, from −δ to +δ, between the two lines.
//  - the joint smoother (joint_smoother.h): one Ceres problem over every
//    sample, with latent tip angles and external torques, priors and a robust
//    loss, and the full covariance of the parameters.

#include <array>
#include <string>
#include <vector>

#include "pliant/estimation/compliance_law_fit.h"
#include "pliant/estimation/identification_data.h"
#include "pliant/models/parameters.h"

namespace pliant::estimation {

/// One joint's estimate at one depth (the points of the paper's Fig. 6).
struct DepthEstimate {
  int joint = 0;  ///< 0 or 1
  double insertion_depth_m = 0.0;
  double inverse_compliance_nm_per_rad = 0.0;  ///< mean slope of the two branch lines
  double inverse_compliance_sd = 0.0;
  double backlash_rad = 0.0;  ///< half the distance between the branch lines
  double backlash_sd = 0.0;
  int loaded_samples = 0;
};

struct IdentificationResult {
  std::string method;                   ///< "paper" or "smoother"
  models::ModelParameters parameters;   ///< with covariance of every estimated number
  std::vector<DepthEstimate> depth_estimates;
  std::array<double, 2> angle_rms_rad{{0.0, 0.0}};  ///< fit residual of q_j (tip_fixed samples)
  std::array<double, 2> effort_rms_nm{{0.0, 0.0}};  ///< fit residual of tau_j
  double condition_number = 0.0;  ///< of the parameters' correlation matrix
  std::vector<std::string> warnings;  ///< what the logs cannot determine, and why
  std::string report;                 ///< solver summary, one line per solve
  double seconds = 0.0;
};

struct PaperProcedureOptions {
  models::ComplianceForm law = models::ComplianceForm::kInverseCubic;  ///< the paper's
  /// A sample is on a branch when |tau − tau_ref| exceeds this (N·m), per
  /// joint: the paper's tau_min. Inside it the shaft crosses the clearance.
  std::array<double, 2> contact_threshold_nm{{0.1, 0.2}};
  double bias_table_step_rad = 5.0 * 3.14159265358979323846 / 180.0;  ///< paper: 5°
  double depth_resolution_m = 1e-3;  ///< depths closer than this are one depth
  double cannula_length_m = 0.025;   ///< for a beam_series law

  bool IsValid(std::string* error) const;
};

/// The paper's model (data/paper.json, built in): the default prior.
models::ModelParameters PaperPrior();

/// `prior` supplies what the logs cannot: tau_min, the dead-zone width, and
/// every parameter a warning says was not identified. Throws
/// std::invalid_argument for invalid options.
IdentificationResult RunPaperProcedure(const IdentificationData& data,
                                       const models::ModelParameters& prior,
                                       const PaperProcedureOptions& options = {});

/// The paper's bias table for joint j: free-tip efforts averaged in bins of
/// `step_rad` of q_j (knot at the bin's mean angle). Empty when no free rows.
models::BiasTorqueTable FitBiasTable(const IdentificationData& data, int joint, double step_rad);

/// Structural identifiability: which parameters the samples cannot determine,
/// each with the reason (no tip_fixed rows, no reversal, one depth only, no
/// free-tip rows). `bias` gives tau0 for the contact test.
std::vector<std::string> IdentifiabilityWarnings(const IdentificationData& data,
                                                 const models::ModelParameters& bias,
                                                 const PaperProcedureOptions& options,
                                                 int law_coefficients);

}  // namespace pliant::estimation
