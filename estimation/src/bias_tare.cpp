#include "pliant/estimation/bias_tare.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace pliant::estimation {
namespace {

// The covariance names of a joint's Fourier bias, each with the mean over the
// rows of tau0's derivative by it (g_k).
std::vector<std::pair<std::string, double>> BiasGradient(const models::JointParameters& joint,
                                                         int index, const TareRows& rows) {
  std::vector<std::pair<std::string, double>> g;
  if (joint.bias_form != models::BiasForm::kFourier) return g;
  const std::string prefix = "joint" + std::to_string(index + 1) + ".bias_torque.";
  const auto& f = joint.bias_fourier;
  const double n = double(std::max<std::size_t>(rows.angle_rad.size(), 1));
  for (std::size_t i = 0; i < f.coefficients.size(); ++i) {
    double sum = 0.0;
    const double k = double((i + 1) / 2);
    for (double q : rows.angle_rad) {
      sum += i == 0 ? 1.0 : i % 2 == 1 ? std::cos(k * q) : std::sin(k * q);
    }
    g.emplace_back(prefix + "coefficients[" + std::to_string(i) + "]", sum / n);
  }
  double depth = 0.0, depth_cos = 0.0, depth_sin = 0.0;
  for (std::size_t r = 0; r < rows.depth_m.size(); ++r) {
    const double lever = rows.depth_m[r] - f.reference_depth_m;
    depth += lever;
    if (r < rows.angle_rad.size()) {
      depth_cos += lever * std::cos(rows.angle_rad[r]);
      depth_sin += lever * std::sin(rows.angle_rad[r]);
    }
  }
  g.emplace_back(prefix + "depth_slope_nm_per_m", depth / n);
  g.emplace_back(prefix + "depth_harmonic_nm_per_m[0]", depth_cos / n);
  g.emplace_back(prefix + "depth_harmonic_nm_per_m[1]", depth_sin / n);
  return g;
}

Eigen::Index IndexOf(const models::ParameterCovariance& c, const std::string& name) {
  const auto it = std::find(c.names.begin(), c.names.end(), name);
  return it == c.names.end() ? -1 : Eigen::Index(it - c.names.begin());
}

// a0 is named in the covariance (a zero row and column if it was not).
Eigen::Index EnsureNamed(models::ParameterCovariance* c, const std::string& name) {
  const Eigen::Index found = IndexOf(*c, name);
  if (found >= 0) return found;
  const Eigen::Index n = c->matrix.rows();
  Eigen::MatrixXd grown = Eigen::MatrixXd::Zero(n + 1, n + 1);
  grown.topLeftCorner(n, n) = c->matrix;
  c->matrix = grown;
  c->names.push_back(name);
  return n;
}

}  // namespace

double BiasSdOver(const models::ModelParameters& parameters, int joint, const TareRows& rows) {
  if (!parameters.covariance) return 0.0;
  const auto& c = *parameters.covariance;
  Eigen::VectorXd g = Eigen::VectorXd::Zero(c.matrix.rows());
  for (const auto& [name, derivative] : BiasGradient(parameters.joints[joint], joint, rows)) {
    const Eigen::Index i = IndexOf(c, name);
    if (i >= 0) g[i] = derivative;
  }
  return std::sqrt(std::max(0.0, g.dot(c.matrix * g)));
}

void TareBiasTorque(int joint, double offset_nm, double offset_sd_nm, const TareRows& rows,
                    const std::string& note, models::ModelParameters* parameters) {
  auto& p = parameters->joints[joint];
  std::string& source = p.sources["bias_torque"];
  source += (source.empty() ? "" : "; ") + note;
  if (p.bias_form == models::BiasForm::kTable) {
    for (double& torque : p.bias_torque.torque_nm) torque += offset_nm;
    return;  // a table carries no covariance to update
  }
  p.bias_fourier.coefficients[0] += offset_nm;
  if (!parameters->covariance) parameters->covariance = models::ParameterCovariance{};
  auto& c = *parameters->covariance;
  const auto gradient = BiasGradient(p, joint, rows);
  const Eigen::Index a0 = EnsureNamed(&c, gradient.front().first);
  // a0' = mean(tau − internal) − Σ_{k≠0} g_k·c_k: row a0 of the map.
  Eigen::MatrixXd map = Eigen::MatrixXd::Identity(c.matrix.rows(), c.matrix.cols());
  map(a0, a0) = 0.0;
  for (std::size_t k = 1; k < gradient.size(); ++k) {
    const Eigen::Index i = IndexOf(c, gradient[k].first);
    if (i >= 0) map(a0, i) = -gradient[k].second;
  }
  c.matrix = map * c.matrix * map.transpose();
  c.matrix(a0, a0) += offset_sd_nm * offset_sd_nm;
}

}  // namespace pliant::estimation
