#pragma once
// The clustered (Liang–Zeger) sandwich covariance of a least-squares fit, shared
// by the quasi-static identification and the joint smoother.
//
// Rows of one cluster (a clamp, a block of free-tip poses) share their errors:
// an unknown start, what the model lacks. White-noise theory counts each row
// as independent information and its σ shrink with the number of rows; the
// sandwich counts each cluster's score g_c = J_cᵀ r_c as one draw:
//
//     Cov = H⁻¹ (c/(c−1) Σ_c g_c g_cᵀ + Σ_model J_mᵀ J_m) H⁻¹,   H = JᵀJ,
//
// with c the number of clusters (the small-sample factor of Liang & Zeger,
// Biometrika 1986). Rows outside every cluster (priors) keep their
// model-based information J_mᵀ J_m: a prior is not a sample whose spread the
// residuals could show. Nuisance unknowns (a tip angle per clamp, an external
// torque per sample) are profiled exactly: each x_c = H⁻¹ g_c is solved in the
// full (sparse) system and only the wanted columns of x_c are kept.

#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <ceres/problem.h>

namespace pliant::estimation::detail {

struct SandwichCovariance {
  Eigen::MatrixXd clustered;  ///< the sandwich over the wanted columns
  Eigen::MatrixXd model;      ///< H⁻¹ over the wanted columns (white, unit-variance residuals)
  int clusters = 0;
  double residual_square_sum = 0.0;
  Eigen::Index rows = 0, columns = 0;
};

/// `cluster_of_row[r]` ≥ 0 names the cluster of row r, −1 a model-based row;
/// `wanted` are the columns whose covariance is returned. Columns that no row
/// touches (a block held constant) get zero variance.
SandwichCovariance ClusteredSandwich(const Eigen::SparseMatrix<double>& jacobian,
                                     const Eigen::VectorXd& residuals,
                                     const std::vector<int>& cluster_of_row,
                                     const std::vector<Eigen::Index>& wanted);

/// The cluster jackknife (CV3 of MacKinnon, Nielsen & Webb, J. Econometrics
/// 2023) for a fit with few parameters and no per-cluster nuisance unknowns:
/// each cluster's leave-one-out shift, one Gauss–Newton step
/// d_c = (H − H_c)⁻¹ g_c, and Cov = (c−1)/c Σ_c d_c d_cᵀ + H⁻¹ J_mᵀ J_m H⁻¹.
/// The Liang–Zeger form solves with all of H; when a few clusters hold most
/// of a parameter's information (a push direction drawn once), their own
/// rows pull the fit toward them, their residuals shrink and it is too
/// small. Dropping the cluster undoes that. A cluster whose removal leaves H
/// singular counts with the pseudo-inverse.
SandwichCovariance JackknifeSandwich(const Eigen::SparseMatrix<double>& jacobian,
                                     const Eigen::VectorXd& residuals,
                                     const std::vector<int>& cluster_of_row);

/// The blocking method (Flyvbjerg & Petersen, J. Chem. Phys. 1989): a
/// cluster must outlast the errors' correlation, which the residual's own
/// autocorrelation understates when white noise hides a slow misfit. The
/// sandwich is taken over `cluster_of_row`'s clusters and over runs of 2, 3,
/// 4, 6, 8, … consecutive ones while at least `min_clusters` remain; the
/// result is not below any of them (NotBelow), `clustered` of the first.
SandwichCovariance BlockedSandwich(const Eigen::SparseMatrix<double>& jacobian,
                                   const Eigen::VectorXd& residuals,
                                   const std::vector<int>& cluster_of_row,
                                   const std::vector<Eigen::Index>& wanted, int min_clusters);

/// The robustified Jacobian (tangent space, columns in the order of `blocks`;
/// blocks not listed are held constant) and residuals of `problem`, rows in the
/// order of `residual_blocks` (all when empty).
void EvaluateJacobian(ceres::Problem* problem, const std::vector<double*>& blocks,
                      const std::vector<ceres::ResidualBlockId>& residual_blocks,
                      Eigen::SparseMatrix<double>* jacobian, Eigen::VectorXd* residuals);

/// The larger of two covariances in the Loewner order that is smallest in the
/// eigenbasis of `floor`: B = F^½ U max(Λ, 1) Uᵀ F^½ with F^-½ A F^-½ = U Λ Uᵀ.
/// A ⪯ B and F ⪯ B; directions F leaves at zero keep A.
Eigen::MatrixXd NotBelow(const Eigen::MatrixXd& a, const Eigen::MatrixXd& floor);

}  // namespace pliant::estimation::detail
