#pragma once
// Fitting a compliance law K(L) to per-depth compliance estimates, and
// comparing laws by held-out error and an information criterion.
//
// The paper (section 5): "a cubic polynomial in L was then fit to the slopes
// of these lines, which provided the inverse of the angular correction factor".
// Each law is linear in its fitted coefficients once written in the right
// variable, so every fit here is a linear least-squares problem:
//   inverse_cubic   1/K = c3·L³ + c2·L² + c1·L + c0
//   direct_cubic      K = c3·L³ + c2·L² + c1·L + c0
//   beam_series       K = c_joint + c_structure/L + f_shaft·(L − l_c)³₊/(3L²), each >= 0,
//                     l_c held at its given value (geometry, not fitted)

#include <string>
#include <vector>

#include <Eigen/Core>

#include "pliant/models/parameters.h"

namespace pliant::estimation {

/// One depth's estimate of 1/K (N·m/rad) and its standard deviation.
struct DepthCompliance {
  double insertion_depth_m = 0.0;
  double inverse_compliance_nm_per_rad = 0.0;
  double inverse_compliance_sd = 0.0;
};

struct ComplianceLawFit {
  models::ComplianceLaw law;
  /// Covariance of the four stored numbers (zero row and column for a beam
  /// law's cannula length, and for any beam term held at its bound of 0).
  Eigen::Matrix4d covariance = Eigen::Matrix4d::Zero();
  int fitted_coefficients = 0;
  double weighted_chi_square = 0.0;  ///< Σ ((1/K_fit − 1/K_i)/sd_i)²
  double rms_inverse_compliance = 0.0;  ///< N·m/rad
};

/// Least squares. `weighted`: weights 1/sd² (otherwise unweighted, as the
/// paper). The covariance propagates the per-depth sd through the fit (so it
/// exists even with as many depths as coefficients) and is inflated by the
/// scatter when the points disagree with the law beyond their sd. Throws
/// std::invalid_argument with fewer depths than coefficients.
ComplianceLawFit FitComplianceLaw(models::ComplianceForm form,
                                  const std::vector<DepthCompliance>& points, bool weighted,
                                  double cannula_length_m = 0.025);

/// How well one law describes the per-depth estimates.
struct LawComparison {
  models::ComplianceForm form;
  int coefficients = 0;
  double held_out_rms = 0.0;  ///< leave-one-depth-out RMS error of 1/K, N·m/rad
  double aic = 0.0;           ///< χ² + 2k (Gaussian errors with the given sd)
  double bic = 0.0;           ///< χ² + k·ln(n)
};

/// All three laws, weighted fits; needs at least 5 depths.
std::vector<LawComparison> CompareComplianceLaws(const std::vector<DepthCompliance>& points,
                                                 double cannula_length_m = 0.025);

}  // namespace pliant::estimation
