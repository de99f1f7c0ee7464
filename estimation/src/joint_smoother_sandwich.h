#pragma once
// The joint smoother's covariance from the clustered sandwich
// (clustered_sandwich.h, docs/decisions/0009-identification-clustered-sandwich-for-the-smoother.md).

#include <vector>

#include <Eigen/Core>
#include <ceres/problem.h>

#include "pliant/estimation/identification_data.h"

namespace pliant::estimation::detail {

/// The cluster of each sample: one per tip_fixed segment (a clamp or divot
/// hold shares its start and its model error), and for free-tip samples
/// contiguous blocks of ⌈n^⅓⌉ samples of each segment of n samples (the
/// block length that keeps a variance estimate consistent under short-range
/// dependence: Hall, Horowitz & Jing, Biometrika 1995). Also the number of
/// clamp clusters and of free-tip blocks.
std::vector<int> SampleClusters(const IdentificationData& data, int* held_clusters,
                                int* free_clusters);

/// One global block of the smoother as the covariance lays it out: its memory,
/// where it starts in the output, its physical scale per coordinate, and the
/// coordinates free in the fit (in tangent order; none when held constant).
struct GlobalBlock {
  double* values = nullptr;
  Eigen::Index offset = 0;
  std::vector<double> scale;
  std::vector<int> free;
};

/// The sandwich of the global blocks (zero rows and columns for what is held),
/// in physical units, `size` × `size`. `nuisance` are the other free blocks
/// (tip angles, external torques); `residual_blocks` and `sample_of_residual`
/// (−1 for a prior) list every residual of the problem.
Eigen::MatrixXd SmootherSandwich(ceres::Problem* problem, const std::vector<GlobalBlock>& globals,
                                 const std::vector<double*>& nuisance,
                                 const std::vector<ceres::ResidualBlockId>& residual_blocks,
                                 const std::vector<int>& sample_of_residual,
                                 const std::vector<int>& cluster_of_sample, Eigen::Index size);

}  // namespace pliant::estimation::detail
