#include "branch_classifier.h"

#include <algorithm>

namespace pliant::estimation::detail {

BranchClassifier::BranchClassifier(const IdentificationData& data,
                                   const models::ModelParameters& bias,
                                   const std::array<double, 2>& threshold_nm) {
  const auto& samples = data.samples;
  bias_measured = std::any_of(samples.begin(), samples.end(),
                              [](const IdentificationSample& s) { return !s.tip_fixed; });
  std::map<int, std::vector<double>> efforts[2];
  for (const auto& s : samples) {
    if (s.tip_fixed) for (int j = 0; j < 2; ++j) efforts[j][s.segment].push_back(s.effort_nm[j]);
  }
  std::map<int, double> median[2];
  for (int j = 0; j < 2; ++j) {
    for (auto& [segment, values] : efforts[j]) {
      std::nth_element(values.begin(), values.begin() + long(values.size() / 2), values.end());
      median[j][segment] = values[values.size() / 2];
    }
  }
  for (int j = 0; j < 2; ++j) {
    side[j].resize(samples.size(), 0);
    reference_effort_nm[j].resize(samples.size(), 0.0);
    for (std::size_t i = 0; i < samples.size(); ++i) {
      const auto& s = samples[i];
      if (!s.tip_fixed) continue;
      const double reference =
          bias_measured ? models::BiasTorqueAt(bias.joints[j], s.angle_rad[j], s.insertion_depth_m)
                        : median[j][s.segment];
      reference_effort_nm[j][i] = reference;
      const double load = s.effort_nm[j] - reference;
      side[j][i] = load > threshold_nm[j] ? 1 : (load < -threshold_nm[j] ? -1 : 0);
    }
  }
}

}  // namespace pliant::estimation::detail
