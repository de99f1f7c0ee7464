#include "pliant/estimation/compliance_law_fit.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/QR>

namespace pliant::estimation {
namespace {

using models::ComplianceForm;

struct LinearFit {
  Eigen::VectorXd coefficients;
  Eigen::MatrixXd covariance;
};

// Least squares y ≈ X·b with per-point sd; the covariance propagates the sd
// through the estimator (A·diag(sd²)·Aᵀ, A the estimator's matrix) and grows
// with the scatter when the points disagree with each other beyond their sd.
LinearFit SolveLinear(const Eigen::MatrixXd& X, const Eigen::VectorXd& y, const Eigen::VectorXd& sd,
                      bool weighted) {
  const Eigen::VectorXd w = weighted ? Eigen::VectorXd(sd.cwiseInverse()) : Eigen::VectorXd::Ones(y.size());
  // Columns scaled to unit norm: L³ and 1 differ by three orders of magnitude.
  const Eigen::MatrixXd WX = w.asDiagonal() * X;
  const Eigen::VectorXd scale = WX.colwise().norm().cwiseMax(1e-300).cwiseInverse();
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(WX * scale.asDiagonal());
  // A = D·(WX·D)⁺·W: the map from y to b.
  const Eigen::MatrixXd pinv = qr.solve(Eigen::MatrixXd::Identity(y.size(), y.size()));
  const Eigen::MatrixXd A = scale.asDiagonal() * pinv * w.asDiagonal();
  LinearFit fit;
  fit.coefficients = A * y;
  fit.covariance = A * sd.cwiseAbs2().asDiagonal() * A.transpose();
  const Eigen::VectorXd z = (y - X * fit.coefficients).cwiseQuotient(sd);
  const long dof = long(y.size()) - long(X.cols());
  if (dof > 0 && z.squaredNorm() / dof > 1.0) fit.covariance *= z.squaredNorm() / dof;
  return fit;
}

double BeamShaftTerm(double depth_m, double cannula_length_m) {
  const double free_length = std::max(0.0, depth_m - cannula_length_m);
  return free_length * free_length * free_length / (3.0 * depth_m * depth_m);
}

}  // namespace

ComplianceLawFit FitComplianceLaw(ComplianceForm form, const std::vector<DepthCompliance>& points,
                                  bool weighted, double cannula_length_m) {
  const int columns = form == ComplianceForm::kBeamSeries ? 3 : 4;
  const long n = long(points.size());
  if (n < columns) {
    throw std::invalid_argument("a " + std::string(models::ComplianceFormName(form)) + " law needs " +
                                std::to_string(columns) + " depths or more, found " +
                                std::to_string(n));
  }
  // In K-space for the direct and beam laws: sd(K) = sd(1/K)·K².
  Eigen::VectorXd y(n), sd(n);
  Eigen::MatrixXd X(n, columns);
  for (long i = 0; i < n; ++i) {
    const auto& p = points[i];
    const double L = p.insertion_depth_m;
    const bool inverse = form == ComplianceForm::kInverseCubic;
    const double k = 1.0 / p.inverse_compliance_nm_per_rad;
    y[i] = inverse ? p.inverse_compliance_nm_per_rad : k;
    sd[i] = std::max(inverse ? p.inverse_compliance_sd : p.inverse_compliance_sd * k * k, 1e-12);
    if (form == ComplianceForm::kBeamSeries) {
      X.row(i) << 1.0, 1.0 / L, BeamShaftTerm(L, cannula_length_m);
    } else {
      X.row(i) << L * L * L, L * L, L, 1.0;
    }
  }
  ComplianceLawFit out;
  out.law.form = form;
  out.fitted_coefficients = columns;
  if (form != ComplianceForm::kBeamSeries) {
    const LinearFit fit = SolveLinear(X, y, sd, weighted);
    for (int i = 0; i < 4; ++i) out.law.cubic.coefficients[i] = fit.coefficients[i];
    out.covariance = fit.covariance;
  } else {
    // Each series compliance is >= 0: the best fit over the subsets of free
    // terms whose solution is feasible (an exact non-negative least squares
    // for three terms).
    double best = std::numeric_limits<double>::infinity();
    for (int mask = 1; mask < 8; ++mask) {
      std::vector<int> used;
      for (int c = 0; c < 3; ++c) if (mask & (1 << c)) used.push_back(c);
      Eigen::MatrixXd Xs(n, long(used.size()));
      for (std::size_t c = 0; c < used.size(); ++c) Xs.col(long(c)) = X.col(used[c]);
      const LinearFit fit = SolveLinear(Xs, y, sd, weighted);
      if ((fit.coefficients.array() < 0.0).any()) continue;
      const Eigen::VectorXd w = weighted ? Eigen::VectorXd(sd.cwiseInverse()) : Eigen::VectorXd::Ones(n);
      const double cost = (y - Xs * fit.coefficients).cwiseProduct(w).squaredNorm();
      if (cost >= best) continue;
      best = cost;
      out.law.cubic.coefficients = {0.0, 0.0, 0.0, cannula_length_m};
      out.covariance.setZero();
      for (std::size_t a = 0; a < used.size(); ++a) {
        out.law.cubic.coefficients[used[a]] = fit.coefficients[long(a)];
        for (std::size_t b = 0; b < used.size(); ++b) {
          out.covariance(used[a], used[b]) = fit.covariance(long(a), long(b));
        }
      }
      out.fitted_coefficients = int(used.size());
    }
  }
  double sum2 = 0.0;
  for (const auto& p : points) {
    const double fitted = 1.0 / models::EvaluateCompliance(
                                    form, out.law.cubic.coefficients.data(), p.insertion_depth_m);
    const double e = fitted - p.inverse_compliance_nm_per_rad;
    sum2 += e * e;
    out.weighted_chi_square += e * e / std::max(p.inverse_compliance_sd * p.inverse_compliance_sd, 1e-24);
  }
  out.rms_inverse_compliance = std::sqrt(sum2 / double(n));
  return out;
}

std::vector<LawComparison> CompareComplianceLaws(const std::vector<DepthCompliance>& points,
                                                 double cannula_length_m) {
  std::vector<LawComparison> out;
  for (ComplianceForm form : {ComplianceForm::kInverseCubic, ComplianceForm::kDirectCubic,
                              ComplianceForm::kBeamSeries}) {
    const ComplianceLawFit all = FitComplianceLaw(form, points, true, cannula_length_m);
    LawComparison c;
    c.form = form;
    c.coefficients = all.fitted_coefficients;
    c.aic = all.weighted_chi_square + 2.0 * c.coefficients;
    c.bic = all.weighted_chi_square + c.coefficients * std::log(double(points.size()));
    double sum2 = 0.0;
    for (std::size_t i = 0; i < points.size(); ++i) {
      std::vector<DepthCompliance> rest = points;
      rest.erase(rest.begin() + long(i));
      const ComplianceLawFit fit = FitComplianceLaw(form, rest, true, cannula_length_m);
      const double predicted = 1.0 / models::EvaluateCompliance(
                                         form, fit.law.cubic.coefficients.data(),
                                         points[i].insertion_depth_m);
      sum2 += std::pow(predicted - points[i].inverse_compliance_nm_per_rad, 2);
    }
    c.held_out_rms = std::sqrt(sum2 / double(points.size()));
    out.push_back(c);
  }
  return out;
}

}  // namespace pliant::estimation
