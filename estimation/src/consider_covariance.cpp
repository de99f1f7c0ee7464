#include "consider_covariance.h"

#include <stdexcept>

#include <Eigen/Cholesky>

namespace pliant::estimation::detail {

ConsiderResult ConsiderCovariance(const Eigen::MatrixXd& covariance,
                                  const std::vector<long>& considered,
                                  const std::vector<double>& prior_sd) {
  const long n = covariance.rows(), k = long(considered.size());
  if (covariance.cols() != n || long(prior_sd.size()) != k) {
    throw std::invalid_argument("consider covariance: mismatched sizes");
  }
  std::vector<bool> is_considered(std::size_t(n), false);
  for (long c : considered) {
    if (c < 0 || c >= n) throw std::invalid_argument("consider covariance: index out of range");
    is_considered[std::size_t(c)] = true;
  }
  std::vector<long> estimated;
  for (long i = 0; i < n; ++i) if (!is_considered[std::size_t(i)]) estimated.push_back(i);
  const long m = long(estimated.size());

  Eigen::MatrixXd c_tt(m, m), c_tc(m, k), c_cc(k, k);
  for (long a = 0; a < m; ++a) {
    for (long b = 0; b < m; ++b) c_tt(a, b) = covariance(estimated[a], estimated[b]);
    for (long b = 0; b < k; ++b) c_tc(a, b) = covariance(estimated[a], considered[b]);
  }
  for (long a = 0; a < k; ++a)
    for (long b = 0; b < k; ++b) c_cc(a, b) = covariance(considered[a], considered[b]);

  // Ccc is bounded by the prior (Ccc ≤ Σc) and positive definite; LDLT copes
  // with the directions the data pin down tightly.
  const Eigen::MatrixXd sensitivity = c_cc.ldlt().solve(c_tc.transpose()).transpose();  // S
  const Eigen::MatrixXd conditional = c_tt - sensitivity * c_tc.transpose();
  Eigen::VectorXd prior_variance(k);
  for (long a = 0; a < k; ++a) prior_variance[a] = prior_sd[std::size_t(a)] * prior_sd[std::size_t(a)];
  const Eigen::MatrixXd cross = sensitivity * prior_variance.asDiagonal();  // S Σc
  const Eigen::MatrixXd estimated_cov = conditional + cross * sensitivity.transpose();

  ConsiderResult out;
  out.covariance = Eigen::MatrixXd::Zero(n, n);
  out.conditional = Eigen::MatrixXd::Zero(n, n);
  for (long a = 0; a < m; ++a) {
    for (long b = 0; b < m; ++b) {
      out.covariance(estimated[a], estimated[b]) = estimated_cov(a, b);
      out.conditional(estimated[a], estimated[b]) = conditional(a, b);
    }
    for (long b = 0; b < k; ++b) {
      out.covariance(estimated[a], considered[b]) = cross(a, b);
      out.covariance(considered[b], estimated[a]) = cross(a, b);
    }
  }
  for (long a = 0; a < k; ++a) out.covariance(considered[a], considered[a]) = prior_variance[a];
  return out;
}

}  // namespace pliant::estimation::detail
