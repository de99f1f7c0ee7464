#pragma once
// The joint smoother's Ceres problem (joint_smoother.h describes the model):
// built from the state, solved in place, and its covariance. Only
// joint_smoother.cpp includes it.

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <memory>
#include <vector>

#include <ceres/ceres.h>
#include <ceres/normal_prior.h>

#include "clustered_sandwich.h"
#include "identification_common.h"
#include "identification_costs.h"
#include "joint_smoother_sandwich.h"
#include "joint_smoother_setup.h"
#include "pliant/estimation/joint_smoother.h"
#include "pliant/models/effects/bias_torque_fourier.h"

namespace pliant::estimation::detail {

inline ceres::CostFunction* Prior(const double* mean, const double* sd, int n) {
  ceres::Matrix a = ceres::Matrix::Zero(n, n);
  ceres::Vector b(n);
  for (int i = 0; i < n; ++i) a(i, i) = 1.0 / sd[i], b[i] = mean[i];
  return new ceres::NormalPrior(a, b);
}

class SmootherProblem {
 public:
  SmootherProblem(const IdentificationData& data, const SmootherPrior& prior,
                  const JointSmootherOptions& options, const SmootherNoise& noise,
                  const UndeterminedParameters& held, SmootherState* state)
      : state_(state), held_(held), huber_(options.robust_loss_sd),
        beam_(options.law == models::ComplianceForm::kBeamSeries),
        estimate_width_(options.estimate_deadzone_width) {
    ceres::Problem::Options problem_options;
    problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    problem_ = std::make_unique<ceres::Problem>(problem_options);
    ordering_ = std::make_shared<ceres::ParameterBlockOrdering>();
    const std::array<models::ComplianceForm, 2> forms{options.law, options.law};
    const bool beam = options.law == models::ComplianceForm::kBeamSeries;
    const int h = options.bias_harmonics;
    const int nb = models::BiasTorqueFourierEffect::ParameterCount(h);
    LayOut(*state, nb);
    for (int j = 0; j < 2; ++j) {
      // The law in units of its prior sd (identification_costs.h says why).
      std::array<double, 4> scaled_mean, unit{1.0, 1.0, 1.0, 1.0};
      for (int i = 0; i < 4; ++i) {
        law_scale_[j][i] = prior.law_sd[j][i];
        law_[j][i] = state->law[j][i] / law_scale_[j][i];
        scaled_mean[i] = prior.law[j][i] / law_scale_[j][i];
      }
      Global(law_[j], 4, scaled_mean.data(), unit.data());
      if (beam) {  // l_c is geometry; the three compliances are >= 0
        problem_->SetManifold(law_[j], new ceres::SubsetManifold(4, {3}));
        for (int i = 0; i < 3; ++i) problem_->SetParameterLowerBound(law_[j], i, 0.0);
      }
      Global(delta_[j], 1, &prior.delta_rad[j], &prior.delta_sd[j]);
      problem_->SetParameterLowerBound(delta_[j], 0, 0.0);
      // w is held in every solve: it is profiled outside (joint_smoother_width.h),
      // since Levenberg–Marquardt crawls where a hard contact drives it to the
      // floor and the dead zone turns into a step.
      Global(width_[j], 1, &prior.log_width[j], &prior.log_width_sd[j]);
      problem_->SetParameterBlockConstant(width_[j]);
      Global(bias_[j], nb, prior.bias[j].data(), prior.bias_sd[j].data());
      held_bias_[j] = HeldBiasCoordinates(h, options.bias_depth_term, held.depth_harmonic[j]);
      if (!held_bias_[j].empty()) {
        problem_->SetManifold(bias_[j], new ceres::SubsetManifold(nb, held_bias_[j]));
      }
      // What the logs cannot determine stays at its prior mean (GlobalCovariance
      // carries its prior sd into the others'): fitted, it would soak up
      // whatever the model misses and report a tiny sd.
      if (held_.backlash[j]) problem_->SetParameterBlockConstant(delta_[j]);
      if (held_.bias[j]) problem_->SetParameterBlockConstant(bias_[j]);
    }
    for (auto& [segment, tip] : tip_) {
      for (int j = 0; j < 2; ++j) {
        // A weak prior (0.1 rad) keeps a tip the samples barely see finite.
        const double sd = 0.1;
        Add(-1, Prior(tip + j, &sd, 1), nullptr, tip + j);
        ordering_->AddElementToGroup(tip + j, 1);
      }
    }
    for (std::size_t i = 0; i < data.samples.size(); ++i) {
      const auto& s = data.samples[i];
      const double rows = std::sqrt(double(s.rows));
      for (int j = 0; j < 2; ++j) {
        if (!s.tip_fixed) {
          Add(int(i),
              NewEffortResidual(s, j, h, options.bias_reference_depth_m,
                                        noise.effort_free_nm[j] / rows, false),
              &huber_, bias_[j]);
          continue;
        }
        double* tau = &state->tau_ext_nm[i][j];
        Add(int(i),
            NewEffortResidual(s, j, h, options.bias_reference_depth_m,
                                      noise.effort_fixed_nm[j] / rows, true),
            &huber_, bias_[j], tau);
        Add(int(i),
            NewAngleResidual(s, j, forms, law_scale_[j], noise.angle_fixed_rad[j] / rows),
            &huber_, tau, tip_.at(s.segment) + j, law_[j], delta_[j], width_[j]);
        ordering_->AddElementToGroup(tau, 0);  // eliminated first (Schur complement)
      }
    }
  }

  ceres::Solver::Summary Solve(const JointSmootherOptions& options) {
    ceres::Solver::Options solver;
    // Reduced system: tips (block diagonal) bordered by the globals, an arrow
    // that sparse Cholesky factors in time linear in the number of segments.
    solver.linear_solver_type = ceres::SPARSE_SCHUR;
    if (ordering_->GroupSize(0) > 0) solver.linear_solver_ordering = ordering_;
    else solver.linear_solver_type = ceres::DENSE_QR;
    solver.max_num_iterations = options.max_iterations;
    solver.num_threads = options.threads;
    solver.function_tolerance = 1e-10;
    solver.parameter_tolerance = 1e-10;
    ceres::Solver::Summary summary;
    ceres::Solve(solver, problem_.get(), &summary);
    CopyBack();
    return summary;
  }

  struct Snapshot {
    std::vector<double> globals;
    std::vector<std::array<double, 2>> tau_ext_nm;
  };
  Snapshot Save() const { return {globals_, state_->tau_ext_nm}; }
  void Restore(const Snapshot& s) {
    std::copy(s.globals.begin(), s.globals.end(), globals_.begin());
    std::copy(s.tau_ext_nm.begin(), s.tau_ext_nm.end(), state_->tau_ext_nm.begin());
    CopyBack();
  }

  // ∂cost/∂log w_j at the current values (the widths freed for the evaluation).
  std::array<double, 2> WidthSlope() {
    for (double* w : width_) problem_->SetParameterBlockVariable(w);
    ceres::Problem::EvaluateOptions evaluate;
    evaluate.parameter_blocks = {width_[0], width_[1]};
    std::vector<double> gradient;
    problem_->Evaluate(evaluate, nullptr, nullptr, &gradient, nullptr);
    for (double* w : width_) problem_->SetParameterBlockConstant(w);
    return {gradient[0], gradient[1]};
  }

  void HoldLogWidths(const std::array<double, 2>& log_width) {
    for (int j = 0; j < 2; ++j) *width_[j] = log_width[j];
  }

  // The covariance is the fit's with w free: its uncertainty is carried into
  // the others' (a profiled parameter's curvature is the full Hessian's).
  void FreeWidths() {
    if (!estimate_width_) return;
    for (int j = 0; j < 2; ++j) problem_->SetParameterBlockVariable(width_[j]);
  }

  // The global blocks as the covariance lays them out: law1, law2, delta1,
  // delta2, log w1, log w2, bias1, bias2, in physical units.
  std::vector<GlobalBlock> Layout() {
    std::vector<GlobalBlock> out;
    Eigen::Index at = 0;
    auto add = [&](double* values, std::vector<double> scale, bool constant,
                   const std::vector<int>& fixed) {
      GlobalBlock b{values, at, std::move(scale), {}};
      for (int i = 0; i < int(b.scale.size()) && !constant; ++i)
        if (std::find(fixed.begin(), fixed.end(), i) == fixed.end()) b.free.push_back(i);
      at += Eigen::Index(b.scale.size());
      out.push_back(std::move(b));
    };
    for (int j = 0; j < 2; ++j) {
      add(law_[j], {law_scale_[j].begin(), law_scale_[j].end()}, false,
          beam_ ? std::vector<int>{3} : std::vector<int>{});
    }
    for (int j = 0; j < 2; ++j) add(delta_[j], {1.0}, held_.backlash[j], {});
    for (int j = 0; j < 2; ++j) add(width_[j], {1.0}, !estimate_width_, {});
    for (int j = 0; j < 2; ++j) {
      const int nb = int(state_->bias[j].size());
      add(bias_[j], std::vector<double>(std::size_t(nb), 1.0), held_.bias[j], held_bias_[j]);
    }
    return out;
  }

  // The clustered sandwich of the globals (joint_smoother_sandwich.h), the
  // tips and external torques profiled; held blocks get zero rows.
  Eigen::MatrixXd Sandwich(const std::vector<int>& cluster_of_sample) {
    std::vector<double*> nuisance;
    for (auto& [segment, tip] : tip_) nuisance.push_back(tip), nuisance.push_back(tip + 1);
    for (auto& tau : state_->tau_ext_nm)
      for (double& t : tau)
        if (problem_->HasParameterBlock(&t)) nuisance.push_back(&t);
    FreeWidths();
    const auto layout = Layout();
    const Eigen::Index size = layout.back().offset + Eigen::Index(layout.back().scale.size());
    return SmootherSandwich(problem_.get(), layout, nuisance, residuals_, sample_of_residual_,
                                    cluster_of_sample, size);
  }

  // Covariance of the Layout() blocks in physical units (white row noise);
  // false when Ceres finds the problem singular.
  bool GlobalCovariance(const JointSmootherOptions& options, double variance_factor,
                        Eigen::MatrixXd* out) {
    std::vector<const double*> blocks;
    std::vector<double> scale;
    for (const auto& b : Layout()) {
      blocks.push_back(b.values);
      scale.insert(scale.end(), b.scale.begin(), b.scale.end());
    }
    FreeWidths();
    // The held parameters are free here: their columns give the sensitivity of
    // the others to them (consider_covariance.h).
    for (int j = 0; j < 2; ++j) {
      if (held_.backlash[j]) problem_->SetParameterBlockVariable(delta_[j]);
      if (held_.bias[j]) problem_->SetParameterBlockVariable(bias_[j]);
    }
    const long n = long(scale.size());
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> c(n, n);
    ceres::Covariance::Options covariance_options;
    covariance_options.num_threads = options.threads;
    ceres::Covariance covariance(covariance_options);
    std::vector<std::pair<const double*, const double*>> pairs;
    for (std::size_t a = 0; a < blocks.size(); ++a)
      for (std::size_t b = a; b < blocks.size(); ++b) pairs.push_back({blocks[a], blocks[b]});
    if (!covariance.Compute(pairs, problem_.get()) ||
        !covariance.GetCovarianceMatrix(blocks, c.data())) {
      return false;
    }
    const Eigen::Map<const Eigen::VectorXd> s(scale.data(), n);
    *out = variance_factor * (s.asDiagonal() * Eigen::MatrixXd(c) * s.asDiagonal());
    return true;
  }

 private:
  template <typename... Blocks>
  void Add(int sample, ceres::CostFunction* cost, ceres::LossFunction* loss, Blocks... blocks) {
    residuals_.push_back(problem_->AddResidualBlock(cost, loss, blocks...));
    sample_of_residual_.push_back(sample);
  }

  // The bias coordinates held at their prior mean: the depth slope without
  // bias_depth_term, the depth harmonic where the free-tip rows leave it open.
  static std::vector<int> HeldBiasCoordinates(int harmonics, bool depth_term,
                                              const std::array<bool, 2>& held_harmonic) {
    using Effect = models::BiasTorqueFourierEffect;
    std::vector<int> out;
    if (!depth_term) out.push_back(Effect::DepthSlopeIndex(harmonics));
    for (int i = 0; i < 2; ++i)
      if (held_harmonic[i]) out.push_back(Effect::DepthHarmonicIndex(harmonics) + i);
    return out;
  }

  void Global(double* block, int n, const double* mean, const double* sd) {
    problem_->AddParameterBlock(block, n);
    Add(-1, Prior(mean, sd, n), nullptr, block);
    ordering_->AddElementToGroup(block, 1);
  }

  // Ceres orders the blocks of one elimination group by address (a
  // ParameterBlockOrdering holds std::set<double*>), and the order changes the
  // solution's last digits: blocks in separate heap allocations would follow
  // the heap's layout, which differs from one process to the next (a Python
  // process, another malloc). Every block outside the eliminated group lives
  // in globals_, in a fixed order: the law (in prior-sd units), δ, log w and
  // the bias of each joint, then the tips by segment.
  void LayOut(const SmootherState& state, int bias_size) {
    globals_.assign(2 * (4 + 1 + 1 + std::size_t(bias_size)) + 2 * state.tip_rad.size(), 0.0);
    double* next = globals_.data();
    auto take = [&next](std::size_t n) { double* block = next; next += n; return block; };
    for (int j = 0; j < 2; ++j) {
      law_[j] = take(4);
      delta_[j] = take(1), *delta_[j] = state.delta_rad[j];
      width_[j] = take(1), *width_[j] = state.log_width[j];
      bias_[j] = take(std::size_t(bias_size));
      std::copy(state.bias[j].begin(), state.bias[j].end(), bias_[j]);
    }
    for (const auto& [segment, tip] : state.tip_rad) {
      tip_[segment] = take(2);
      std::copy(tip.begin(), tip.end(), tip_[segment]);
    }
  }

  void CopyBack() {
    for (int j = 0; j < 2; ++j) {
      for (int i = 0; i < 4; ++i) state_->law[j][i] = law_[j][i] * law_scale_[j][i];
      state_->delta_rad[j] = *delta_[j];
      state_->log_width[j] = *width_[j];
      std::copy(bias_[j], bias_[j] + state_->bias[j].size(), state_->bias[j].begin());
    }
    for (auto& [segment, tip] : state_->tip_rad) std::copy(tip_[segment], tip_[segment] + 2, tip.begin());
  }

  SmootherState* state_;
  UndeterminedParameters held_;
  std::vector<double> globals_;
  double *law_[2], *delta_[2], *width_[2], *bias_[2];
  std::map<int, double*> tip_;
  std::array<std::array<double, 4>, 2> law_scale_{};
  ceres::HuberLoss huber_;
  std::array<std::vector<int>, 2> held_bias_;  // HeldBiasCoordinates per joint
  bool beam_, estimate_width_;
  std::vector<ceres::ResidualBlockId> residuals_;
  std::vector<int> sample_of_residual_;  // −1: a prior
  std::unique_ptr<ceres::Problem> problem_;
  std::shared_ptr<ceres::ParameterBlockOrdering> ordering_;
};

}  // namespace pliant::estimation::detail
