#include "clustered_sandwich.h"

#include <algorithm>
#include <stdexcept>

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <Eigen/SparseCholesky>
#include <ceres/crs_matrix.h>

namespace pliant::estimation::detail {
namespace {

// Solves H X = B and keeps the wanted rows of X.
Eigen::MatrixXd SolveWanted(const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>& h,
                            const Eigen::MatrixXd& b, const std::vector<Eigen::Index>& wanted) {
  const Eigen::MatrixXd x = h.solve(b);
  Eigen::MatrixXd out(Eigen::Index(wanted.size()), b.cols());
  for (std::size_t i = 0; i < wanted.size(); ++i) out.row(Eigen::Index(i)) = x.row(wanted[i]);
  return out;
}

}  // namespace

SandwichCovariance ClusteredSandwich(const Eigen::SparseMatrix<double>& jacobian,
                                     const Eigen::VectorXd& residuals,
                                     const std::vector<int>& cluster_of_row,
                                     const std::vector<Eigen::Index>& wanted) {
  if (Eigen::Index(cluster_of_row.size()) != jacobian.rows() || residuals.size() != jacobian.rows())
    throw std::invalid_argument("ClusteredSandwich: one cluster label and residual per row");
  const Eigen::Index n = jacobian.cols();
  Eigen::SparseMatrix<double> h = Eigen::SparseMatrix<double>(jacobian.transpose()) * jacobian;
  // A column no row touches (a block held constant) stays out of the fit.
  std::vector<bool> untouched(std::size_t(n), false);
  for (Eigen::Index c = 0; c < n; ++c) {
    if (h.coeff(c, c) == 0.0) untouched[std::size_t(c)] = true, h.coeffRef(c, c) = 1.0;
  }
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> factor(h);
  if (factor.info() != Eigen::Success)
    throw std::runtime_error("the clustered sandwich: the fit's information matrix is singular");

  SandwichCovariance out;
  out.rows = jacobian.rows(), out.columns = n;
  out.residual_square_sum = residuals.squaredNorm();
  out.clusters = 1 + *std::max_element(cluster_of_row.begin(), cluster_of_row.end());
  // Scores of the clusters, and the model-based rows as columns of J_mᵀ.
  Eigen::MatrixXd scores = Eigen::MatrixXd::Zero(n, std::max(out.clusters, 0));
  std::vector<Eigen::Index> model_rows;
  const Eigen::SparseMatrix<double, Eigen::RowMajor> rows = jacobian;
  for (Eigen::Index r = 0; r < rows.rows(); ++r) {
    const int c = cluster_of_row[std::size_t(r)];
    if (c < 0) { model_rows.push_back(r); continue; }
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(rows, r); it; ++it)
      scores(it.col(), c) += it.value() * residuals[r];
  }
  Eigen::MatrixXd model = Eigen::MatrixXd::Zero(n, Eigen::Index(model_rows.size()));
  for (std::size_t k = 0; k < model_rows.size(); ++k) {
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(rows, model_rows[k]); it; ++it)
      model(it.col(), Eigen::Index(k)) = it.value();
  }
  const double small_sample = out.clusters > 1 ? double(out.clusters) / (out.clusters - 1) : 1.0;
  const Eigen::MatrixXd x = SolveWanted(factor, scores, wanted);
  const Eigen::MatrixXd m = SolveWanted(factor, model, wanted);
  out.clustered = small_sample * x * x.transpose() + m * m.transpose();
  Eigen::MatrixXd unit = Eigen::MatrixXd::Zero(n, Eigen::Index(wanted.size()));
  for (std::size_t i = 0; i < wanted.size(); ++i) unit(wanted[i], Eigen::Index(i)) = 1.0;
  out.model = SolveWanted(factor, unit, wanted);
  for (std::size_t i = 0; i < wanted.size(); ++i) {
    if (!untouched[std::size_t(wanted[i])]) continue;
    for (auto* c : {&out.clustered, &out.model})
      c->row(Eigen::Index(i)).setZero(), c->col(Eigen::Index(i)).setZero();
  }
  return out;
}

SandwichCovariance JackknifeSandwich(const Eigen::SparseMatrix<double>& jacobian,
                                     const Eigen::VectorXd& residuals,
                                     const std::vector<int>& cluster_of_row) {
  if (Eigen::Index(cluster_of_row.size()) != jacobian.rows() || residuals.size() != jacobian.rows())
    throw std::invalid_argument("JackknifeSandwich: one cluster label and residual per row");
  const Eigen::MatrixXd j = jacobian;
  const Eigen::Index n = j.cols();
  SandwichCovariance out;
  out.rows = j.rows(), out.columns = n;
  out.residual_square_sum = residuals.squaredNorm();
  out.clusters = 1 + *std::max_element(cluster_of_row.begin(), cluster_of_row.end());
  std::vector<Eigen::MatrixXd> information(std::size_t(std::max(out.clusters, 0)), Eigen::MatrixXd::Zero(n, n));
  Eigen::MatrixXd scores = Eigen::MatrixXd::Zero(n, std::max(out.clusters, 0));
  Eigen::MatrixXd model_information = Eigen::MatrixXd::Zero(n, n);
  for (Eigen::Index r = 0; r < j.rows(); ++r) {
    const int c = cluster_of_row[std::size_t(r)];
    const Eigen::VectorXd row = j.row(r).transpose();
    if (c < 0) { model_information += row * row.transpose(); continue; }
    information[std::size_t(c)] += row * row.transpose();
    scores.col(c) += row * residuals[r];
  }
  Eigen::MatrixXd h = model_information;
  for (const auto& hc : information) h += hc;
  const Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> all(h);
  out.model = all.pseudoInverse();
  Eigen::MatrixXd meat = Eigen::MatrixXd::Zero(n, n);
  for (int c = 0; c < out.clusters; ++c) {
    const Eigen::VectorXd shift =
        Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd>(h - information[std::size_t(c)])
            .solve(scores.col(c));
    meat += shift * shift.transpose();
  }
  const double small_sample = out.clusters > 1 ? double(out.clusters - 1) / out.clusters : 1.0;
  out.clustered = small_sample * meat + out.model * model_information * out.model;
  return out;
}

void EvaluateJacobian(ceres::Problem* problem, const std::vector<double*>& blocks,
                      const std::vector<ceres::ResidualBlockId>& residual_blocks,
                      Eigen::SparseMatrix<double>* jacobian, Eigen::VectorXd* residuals) {
  ceres::Problem::EvaluateOptions evaluate;
  evaluate.parameter_blocks = blocks;
  evaluate.residual_blocks = residual_blocks;
  std::vector<double> r;
  ceres::CRSMatrix crs;
  problem->Evaluate(evaluate, nullptr, &r, nullptr, &crs);
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(crs.values.size());
  for (int row = 0; row < crs.num_rows; ++row) {
    for (int k = crs.rows[std::size_t(row)]; k < crs.rows[std::size_t(row) + 1]; ++k)
      entries.emplace_back(row, crs.cols[std::size_t(k)], crs.values[std::size_t(k)]);
  }
  jacobian->resize(crs.num_rows, crs.num_cols);
  jacobian->setFromTriplets(entries.begin(), entries.end());
  *residuals = Eigen::Map<const Eigen::VectorXd>(r.data(), Eigen::Index(r.size()));
}

SandwichCovariance BlockedSandwich(const Eigen::SparseMatrix<double>& jacobian,
                                   const Eigen::VectorXd& residuals,
                                   const std::vector<int>& cluster_of_row,
                                   const std::vector<Eigen::Index>& wanted, int min_clusters) {
  SandwichCovariance out = ClusteredSandwich(jacobian, residuals, cluster_of_row, wanted);
  std::vector<int> merged(cluster_of_row.size());
  // Run lengths about √2 apart: 2, 3, 4, 6, 8, 12, …
  for (int run = 2; out.clusters / run >= min_clusters; run = run % 3 == 0 ? run * 4 / 3 : run * 3 / 2) {
    for (std::size_t r = 0; r < merged.size(); ++r)
      merged[r] = cluster_of_row[r] < 0 ? -1 : cluster_of_row[r] / run;
    const SandwichCovariance longer = ClusteredSandwich(jacobian, residuals, merged, wanted);
    out.clustered = NotBelow(out.clustered, longer.clustered);
  }
  return out;
}

Eigen::MatrixXd NotBelow(const Eigen::MatrixXd& a, const Eigen::MatrixXd& floor) {
  // In units of the floor's sd: the parameters' scales differ by 10¹⁵ (a law
  // coefficient against a clearance in rad), beyond what one eigenvalue
  // threshold can tell apart.
  Eigen::VectorXd unit = floor.diagonal().cwiseMax(0.0).cwiseSqrt();
  for (Eigen::Index i = 0; i < unit.size(); ++i) if (unit[i] == 0.0) unit[i] = 1.0;
  const Eigen::VectorXd per_unit = unit.cwiseInverse();
  const Eigen::MatrixXd scaled_floor = per_unit.asDiagonal() * floor * per_unit.asDiagonal();
  const Eigen::MatrixXd scaled_a = per_unit.asDiagonal() * a * per_unit.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> f(scaled_floor);
  const double tiny = 1e-12 * std::max(f.eigenvalues().maxCoeff(), 0.0);
  Eigen::VectorXd root = f.eigenvalues(), inverse_root = f.eigenvalues();
  for (Eigen::Index i = 0; i < root.size(); ++i) {
    const bool kept = root[i] > tiny;
    root[i] = kept ? std::sqrt(root[i]) : 0.0;
    inverse_root[i] = kept ? 1.0 / root[i] : 0.0;
  }
  const Eigen::MatrixXd half = f.eigenvectors() * root.asDiagonal() * f.eigenvectors().transpose();
  const Eigen::MatrixXd inverse_half =
      f.eigenvectors() * inverse_root.asDiagonal() * f.eigenvectors().transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> ratio(inverse_half * scaled_a * inverse_half);
  // Raise each direction where A is below F to F; leave the others. (Directions
  // F leaves at zero: half·v = 0, nothing is added.)
  const Eigen::VectorXd raise = (1.0 - ratio.eigenvalues().array()).max(0.0).matrix();
  const Eigen::MatrixXd u = unit.asDiagonal() * half * ratio.eigenvectors();
  Eigen::MatrixXd out = a + u * raise.asDiagonal() * u.transpose();
  for (Eigen::Index i = 0; i < out.rows(); ++i) {  // held in both: exactly zero, not round-off
    if (floor(i, i) == 0.0 && a(i, i) == 0.0) out.row(i).setZero(), out.col(i).setZero();
  }
  return out;
}

}  // namespace pliant::estimation::detail
