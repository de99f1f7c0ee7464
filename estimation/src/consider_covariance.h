#pragma once
// Schmidt's consider covariance: the uncertainty of parameters estimated with
// others ("considered") held at their prior mean, because the data cannot
// determine them, including what the considered ones' prior uncertainty does
// to the estimates.
//
// With H the information of the linearised fit (data and priors), θ the
// estimated and c the considered parameters, held at their prior mean with
// prior covariance Σc, the estimate moves with c by S = ∂θ̂/∂c = −Hθθ⁻¹ Hθc,
// and
//     Cov(θ̂) = Hθθ⁻¹ + S Σc Sᵀ,   Cov(θ̂, c) = S Σc,   Cov(c) = Σc.
// Both pieces come from the covariance C = H⁻¹ of the problem with c free
// (with its prior): by the block inverse, Hθθ⁻¹ = Cθθ − Cθc Ccc⁻¹ Ccθ and
// S = Cθc Ccc⁻¹. A variance factor scaling C scales Hθθ⁻¹ and leaves S.

#include <vector>

#include <Eigen/Core>

namespace pliant::estimation::detail {

struct ConsiderResult {
  Eigen::MatrixXd covariance;   ///< of every parameter, as above
  Eigen::MatrixXd conditional;  ///< Hθθ⁻¹ alone (had c been known); zero rows, columns for c
};

/// `covariance` is C (every parameter free, the considered ones with their
/// prior); `considered` their indices in it, `prior_sd` their prior sd in the
/// same order. Throws std::invalid_argument on mismatched sizes.
ConsiderResult ConsiderCovariance(const Eigen::MatrixXd& covariance,
                                  const std::vector<long>& considered,
                                  const std::vector<double>& prior_sd);

}  // namespace pliant::estimation::detail
