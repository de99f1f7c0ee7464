#include "joint_smoother_sandwich.h"

#include <cmath>
#include <map>

#include <ceres/cost_function.h>

#include "clustered_sandwich.h"

namespace pliant::estimation::detail {

std::vector<int> SampleClusters(const IdentificationData& data, int* held_clusters,
                                int* free_clusters) {
  std::vector<int> cluster(data.samples.size(), -1);
  std::map<int, int> clamp;  // segment -> cluster
  for (std::size_t i = 0; i < data.samples.size(); ++i) {
    const auto& s = data.samples[i];
    if (s.tip_fixed) cluster[i] = clamp.emplace(s.segment, int(clamp.size())).first->second;
  }
  *held_clusters = int(clamp.size());
  int next = int(clamp.size());
  std::map<int, std::vector<std::size_t>> free;  // segment -> its samples, in order
  for (std::size_t i = 0; i < data.samples.size(); ++i)
    if (!data.samples[i].tip_fixed) free[data.samples[i].segment].push_back(i);
  for (const auto& [segment, samples] : free) {
    const std::size_t block = std::size_t(std::ceil(std::cbrt(double(samples.size()))));
    for (std::size_t k = 0; k < samples.size(); ++k) {
      if (k % block == 0) ++next;
      cluster[samples[k]] = next - 1;
    }
  }
  *free_clusters = next - *held_clusters;
  return cluster;
}

Eigen::MatrixXd SmootherSandwich(ceres::Problem* problem, const std::vector<GlobalBlock>& globals,
                                 const std::vector<double*>& nuisance,
                                 const std::vector<ceres::ResidualBlockId>& residual_blocks,
                                 const std::vector<int>& sample_of_residual,
                                 const std::vector<int>& cluster_of_sample, Eigen::Index size) {
  std::vector<double*> blocks;
  std::vector<Eigen::Index> wanted, output;  // tangent column -> output index
  std::vector<double> scale;
  Eigen::Index column = 0;
  for (const auto& g : globals) {
    if (g.free.empty()) continue;
    blocks.push_back(g.values);
    for (int i : g.free) {
      wanted.push_back(column++);
      output.push_back(g.offset + i);
      scale.push_back(g.scale[std::size_t(i)]);
    }
  }
  blocks.insert(blocks.end(), nuisance.begin(), nuisance.end());
  std::vector<int> cluster_of_row;
  for (std::size_t k = 0; k < residual_blocks.size(); ++k) {
    const int rows = problem->GetCostFunctionForResidualBlock(residual_blocks[k])->num_residuals();
    const int sample = sample_of_residual[k];
    cluster_of_row.insert(cluster_of_row.end(), std::size_t(rows),
                          sample < 0 ? -1 : cluster_of_sample[std::size_t(sample)]);
  }
  Eigen::SparseMatrix<double> jacobian;
  Eigen::VectorXd residuals;
  EvaluateJacobian(problem, blocks, residual_blocks, &jacobian, &residuals);
  const SandwichCovariance s = ClusteredSandwich(jacobian, residuals, cluster_of_row, wanted);
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(size, size);
  for (std::size_t a = 0; a < output.size(); ++a)
    for (std::size_t b = 0; b < output.size(); ++b)
      out(output[a], output[b]) = scale[a] * s.clustered(Eigen::Index(a), Eigen::Index(b)) * scale[b];
  return out;
}

}  // namespace pliant::estimation::detail
