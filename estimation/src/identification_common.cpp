#include "identification_common.h"

#include <chrono>

#include <Eigen/Eigenvalues>

namespace pliant::estimation::detail {

std::vector<std::string> LawNames(int joint, models::ComplianceForm form) {
  const std::string prefix = "joint" + std::to_string(joint + 1) + ".compliance.";
  if (form == models::ComplianceForm::kBeamSeries) {
    return {prefix + "joint_compliance_rad_per_nm", prefix + "structure_compliance_rad_per_n",
            prefix + "shaft_flexibility_per_nm2", prefix + "cannula_length_m"};
  }
  return {prefix + "c3", prefix + "c2", prefix + "c1", prefix + "c0"};
}

double CorrelationCondition(const Eigen::MatrixXd& covariance) {
  std::vector<Eigen::Index> kept;  // parameters held constant have no variance
  for (Eigen::Index i = 0; i < covariance.rows(); ++i) {
    if (covariance(i, i) > 0.0) kept.push_back(i);
  }
  if (kept.empty()) return 0.0;
  Eigen::MatrixXd correlation(kept.size(), kept.size());
  for (std::size_t a = 0; a < kept.size(); ++a) {
    for (std::size_t b = 0; b < kept.size(); ++b) {
      correlation(a, b) = covariance(kept[a], kept[b]) /
                          std::sqrt(covariance(kept[a], kept[a]) * covariance(kept[b], kept[b]));
    }
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(correlation);
  const double smallest = std::max(eigen.eigenvalues().minCoeff(), 1e-300);
  return eigen.eigenvalues().maxCoeff() / smallest;
}

double NowSeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

double SecondsSince(double start) { return NowSeconds() - start; }

}  // namespace pliant::estimation::detail
