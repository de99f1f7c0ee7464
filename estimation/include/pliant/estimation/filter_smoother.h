#pragma once
// The best estimate after the fact: a Rauch–Tung–Striebel smoother over a
// whole log, run on the online filter's own passes. Forward, Add() steps the
// ComplianceFilter and keeps each joint block's filtered state and the
// transition that produced it; Smooth() then runs backward, per joint block:
//
//   P⁻ₖ₊₁ = F P̂ₖ Fᵀ + Q                    (F, Q of step k+1, as the filter used them)
//   Cₖ    = P̂ₖ Fᵀ (P⁻ₖ₊₁)⁻¹
//   xˢₖ   = x̂ₖ + Cₖ (xˢₖ₊₁ − x⁻ₖ₊₁)
//   Pˢₖ   = P̂ₖ + Cₖ (Pˢₖ₊₁ − P⁻ₖ₊₁) Cₖᵀ
//
// Memory: one SmootherStep (about 1 kB) per sample, for random access to
// every smoothed estimate. `pliant filter --smooth` does not use this class:
// it runs the same steps checkpointed (estimation/src/smoothed_pass.h), a
// filter copy every block of samples and each block recomputed backward,
// memory growing as √N, with the same output to the bit. Measured with
// bench/filter_smooth_log_bench (each pass in a child process, 2 shared
// cores under load): 10⁷ rows, `filter` 30.8 s and 4.9 MB peak resident,
// `filter --smooth` 73.8 s (2.4×) and 73 MB; an earlier run 43.3 s against
// 88.3 s (2.0×). 10⁶ simulated free-motion rows: 4.4 s / 24 MB against
// 8.3 s / 42 MB, where this class (the whole log in memory) took 14.1 s and
// 1.17 GB. bench/long_log_memory.sh, 10⁷ free-motion rows: 50 s / 147 MB
// against 102 s (2.0×) / 148 MB (the reader's and writer's share dominates).
// Not real-time: this is for offline tools.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "pliant/estimation/filter.h"

namespace pliant::estimation {

/// One sample's record for the backward pass: each joint block's filtered
/// (then smoothed) state and the transition that reached it, and what the
/// estimate needs besides (the measurements' NIS and flags stay the filter's).
struct SmootherStep {
  FilterJointState state[2];
  FilterTransition transition[2];
  Eigen::Vector2d encoder_rad{0.0, 0.0};
  double depth_m = 0.0;  ///< the last finite depth (a NaN depth keeps the previous one)
  double nis = 0.0;
  int nis_dof = 0;
  std::uint32_t flags = 0;
};

/// The record of the sample the filter's state has just reached;
/// `previous_depth_m` is the last record's depth (unused when `first`).
SmootherStep RecordStep(const ComplianceFilter& filter, double previous_depth_m, bool first);
/// One backward step: `here` (filtered) becomes smoothed, given the smoothed
/// record that follows it.
void SmoothStep(SmootherStep* here, const SmootherStep& next);
/// The estimate a record holds.
FilterEstimate StepEstimate(const SmootherStep& step);

class FilterSmoother {
 public:
  /// Throws as ComplianceFilter's constructor does.
  FilterSmoother(const models::ModelParameters& parameters, const FilterOptions& options = {});

  /// Reserves room for `samples` steps (optional; avoids regrowth).
  void Reserve(std::size_t samples);

  /// Filters one sample and records it; returns the filter's estimate.
  FilterEstimate Add(const FilterSample& sample);

  /// The backward pass (after the filter's held-back samples, if any). After
  /// it, Estimate(k) is the smoothed estimate of every added sample.
  void Smooth();

  /// Samples recorded: all of them after Smooth(); before, up to
  /// alignment_steps() fewer than added.
  std::size_t size() const { return steps_.size(); }
  /// The estimate at sample k: filtered before Smooth(), smoothed after. The
  /// NIS and flags are always the filter's (they describe the measurements).
  FilterEstimate Estimate(std::size_t k) const { return StepEstimate(steps_.at(k)); }

 private:
  void Record();

  ComplianceFilter filter_;
  std::vector<SmootherStep> steps_;
  bool smoothed_ = false;
};

}  // namespace pliant::estimation
