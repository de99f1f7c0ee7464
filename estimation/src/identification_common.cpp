#include "identification_common.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>

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

std::set<int> ClampsThatLoad(const IdentificationData& data, int j) {
  std::map<int, std::pair<double, double>> range;  // segment -> (lowest, highest) effort
  for (const auto& s : data.samples) {
    if (!s.tip_fixed || !std::isfinite(s.effort_nm[j])) continue;
    auto [it, added] = range.try_emplace(s.segment, s.effort_nm[j], s.effort_nm[j]);
    it->second.first = std::min(it->second.first, s.effort_nm[j]);
    it->second.second = std::max(it->second.second, s.effort_nm[j]);
  }
  double widest = 0.0;
  for (const auto& [segment, r] : range) widest = std::max(widest, r.second - r.first);
  std::set<int> out;
  for (const auto& [segment, r] : range) {
    if (r.second - r.first >= 0.2 * widest) out.insert(segment);
  }
  return out;
}

double NowSeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

double SecondsSince(double start) { return NowSeconds() - start; }

}  // namespace pliant::estimation::detail
