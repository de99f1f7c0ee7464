#pragma once
// Smooth bias torque tau0(q, L): the paper's table (effort averaged at each
// angle, linearly interpolated) has a kink at every knot and no depth term; a
// short Fourier series in the joint angle is smooth, periodic like the
// counterbalance geometry, and needs a handful of numbers instead of ~40.

#include <string>
#include <vector>

#include "pliant/models/effect.h"
#include "pliant/models/parameters.h"

namespace pliant::models {

/// Each joint: tau0_j = a0 + Σ_k [a_k·cos(k·q_j) + b_k·sin(k·q_j)]
///                      + (L − L_ref)·(s_j + c1·cos q_j + d1·sin q_j)   (N·m).
/// Parameters per joint, joint 1's first: a0, a1, b1, …, a_n, b_n, s, c1, d1
/// (2n + 4 numbers). The harmonic count and L_ref are configuration.
class BiasTorqueFourierEffect {
 public:
  static constexpr EffectInfo kInfo{
      "bias_torque_fourier", Channel::kInternalTorque,
      "effort spent against counterbalance and gravity, smooth in the joint angle; its level "
      "and its first harmonic grow linearly with depth"};

  explicit BiasTorqueFourierEffect(int harmonics = 2, double reference_depth_m = 0.155);

  /// Parameters per joint, and where the depth terms sit among them.
  static constexpr int ParameterCount(int harmonics) { return 2 * harmonics + 4; }
  static constexpr int DepthSlopeIndex(int harmonics) { return 2 * harmonics + 1; }
  static constexpr int DepthHarmonicIndex(int harmonics) { return 2 * harmonics + 2; }
  int JointParameterCount() const { return ParameterCount(harmonics_); }
  std::vector<ParameterSpec> Parameters() const;

  template <typename T>
  Vec2<T> operator()(const T* p, const JointState<T>& state) const {
    const int n = JointParameterCount();
    Vec2<T> out;
    for (int j = 0; j < 2; ++j) {
      const T* c = p + j * n;
      out[j] = EvaluateFourierBias(c, harmonics_, c[DepthSlopeIndex(harmonics_)],
                                   c + DepthHarmonicIndex(harmonics_), reference_depth_m_,
                                   state.encoder_angle_rad[j], state.insertion_depth_m);
    }
    return out;
  }

 private:
  int harmonics_;
  double reference_depth_m_;
};

}  // namespace pliant::models
