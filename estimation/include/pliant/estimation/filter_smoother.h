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
// Memory: about 970 bytes per sample (900,000 samples: 0.9 GB).
// Not real-time: this is for offline tools (`pliant filter --smooth`).

#include <cstddef>
#include <cstdint>
#include <vector>

#include "pliant/estimation/filter.h"

namespace pliant::estimation {

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
  FilterEstimate Estimate(std::size_t k) const;

 private:
  struct JointRecord {
    FilterJointState state;  // filtered, then smoothed in place
    FilterTransition transition;
  };
  struct StepRecord {
    JointRecord joint[2];
    Eigen::Vector2d encoder_rad;
    double depth_m;
    double nis;
    int nis_dof;
    std::uint32_t flags;
  };

  void Record();

  ComplianceFilter filter_;
  std::vector<StepRecord> steps_;
  bool smoothed_ = false;
};

}  // namespace pliant::estimation
