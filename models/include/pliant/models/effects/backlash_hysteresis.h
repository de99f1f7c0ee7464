#pragma once
// Backlash with memory: where the shaft sits inside the cannula clearance
// depends on the load history, not on the present load alone. A load well
// beyond the dead-zone width w holds the shaft on the wall it points at; at
// low load nothing holds it and it stays where it was. Under a steady load the
// offset settles at the dead-zone position of backlash.h, delta·S(tau/w).
//
// The memory is a state, the backlash offset b (rad, |b| <= delta), advanced
// once per sample by BacklashHysteresisStep:
//
//   p  = delta·S(tau/w)                      (S: smooth.h's saturation)
//   g  = S(tau/w)²                           (how firmly the load holds the shaft)
//   b+ = b + g·(p − b) − (1 − g)·r·b         while (p − b)·tau >= 0
//   b+ = b − (1 − g)·r·b                     otherwise (the shaft is nearer
//                                            tau's wall than p)
//
// so |tau| >= w puts the shaft exactly on the wall (g = 1, p = ±delta), and at
// |tau| << w the shaft barely moves (g ≈ (15·tau/8w)²). A load only pushes:
// it moves the shaft toward the wall it points at and never back toward the
// middle. A shaft already nearer that wall than p stays there — a load easing
// from 2w to w/2 leaves it on its wall, as a real clearance does; pulling it
// back to p (the dead-zone position) was evidence the filter counted afresh
// every sample while the load held, and it drove the compliance scale and
// the held tip away (docs/filter.md, "The backlash step"). r in [0, 1] is the
// fraction by which an unloaded shaft forgets its wall in this sample
// (the filter: r = 1 − exp(−|Δq|/(c·δ)) for an encoder increment Δq; 0: it
// never does): nothing holds an unloaded shaft on a wall, so as the arm moves
// on, the knowledge of where it sits relaxes to the middle of the clearance (the filter pairs this
// with process noise that relaxes the variance to the uniform's δ²/3). g is a per-sample
// fraction: at 1.5 kHz, effort noise of 0.06·w relaxes a free shaft toward
// the centre with a time constant of about 50 ms; a filter that keeps b
// gives it process noise in proportion to 1 − g, and a fixed tip lets the
// encoders see it directly. b+ and g are continuous in tau and b, and so are
// their derivatives but where p = b (the push meets the shaft): the filter
// differentiates the step with ceres::Jet.
//
// As a memoryless effect (the catalogue's interface) it is the steady state,
// delta·S(tau/w): the dead-zone deflection. The online filter and a simulator
// that keep b call the step themselves.

#include <string>
#include <vector>

#include "pliant/models/effect.h"
#include "pliant/models/effects/backlash.h"
#include "pliant/models/smooth.h"

namespace pliant::models {

/// g = S(tau/w)²: how firmly a load tau (N·m) holds the shaft on a wall, 0 at
/// no load, 1 from the dead-zone width w (N·m, > 0) on.
template <typename T>
T BacklashHold(const T& external_torque_nm, double width_nm) {
  const T saturation = SmoothSaturation(external_torque_nm / width_nm);
  return saturation * saturation;
}

/// The offset b+ (rad) after one sample at external torque tau (N·m), from the
/// offset b (rad), for backlash delta (rad) and dead-zone width w (N·m, > 0);
/// relax (in [0, 1]) is the fraction an unloaded shaft forgets this sample;
/// hold is g = BacklashHold(tau, w). delta may be a T itself (the filter's
/// clearance with its error state). The filter passes g as a constant, so
/// that its Jacobian has no ∂g/∂tau: g is a smooth stand-in for whether a
/// contact holds the shaft, and at low load its slope times the distance to
/// the target (up to 2δ) tied b to every effort sample's noise, a correlation
/// a clearance does not have — a shaft's place does not follow the size of a
/// small load. Through it the held tip and b drifted by δ over a few seconds
/// of an unloaded joint (docs/filter.md, "The backlash step").
template <typename T, typename Delta, typename Hold>
T BacklashHysteresisStep(const T& offset_rad, const T& external_torque_nm, const Delta& delta_rad,
                         double width_nm, double relax, const Hold& hold) {
  const T push = delta_rad * SmoothSaturation(external_torque_nm / width_nm) - offset_rad;
  const T forget = (T(1.0) - hold) * (relax * offset_rad);
  if (push * external_torque_nm >= T(0.0)) return offset_rad + hold * push - forget;
  return offset_rad - forget;
}

/// The same, with g = BacklashHold(tau, w) computed here (the simulation of the
/// model's own truth, where nothing is differentiated).
template <typename T, typename Delta = double>
T BacklashHysteresisStep(const T& offset_rad, const T& external_torque_nm, const Delta& delta_rad,
                         double width_nm, double relax = 0.0) {
  return BacklashHysteresisStep(offset_rad, external_torque_nm, delta_rad, width_nm, relax,
                                BacklashHold(external_torque_nm, width_nm));
}

/// Catalogue form: the steady state delta_j·S(tau_j/w_j) per joint (rad).
/// Parameters: delta1, delta2 (rad), width1, width2 (N·m).
class BacklashHysteresisEffect {
 public:
  static constexpr EffectInfo kInfo{
      "backlash_hysteresis", Channel::kDeflection,
      "the load pushes the shaft across the cannula clearance and it stays where it was pushed "
      "until a load pushes it back (memory state: the offset inside the clearance)"};

  explicit BacklashHysteresisEffect(double delta1_rad = 0.008478, double delta2_rad = 0.007176,
                                    double width1_nm = 0.1, double width2_nm = 0.2)
      : defaults_{delta1_rad, delta2_rad, width1_nm, width2_nm} {}

  std::vector<ParameterSpec> Parameters() const {
    // Priors as for the dead-zone backlash: the clearance is a few mrad, the
    // width a fraction of a N·m.
    return {{"delta1", "rad", defaults_[0], 0.0, 0.05, 0.005},
            {"delta2", "rad", defaults_[1], 0.0, 0.05, 0.005},
            {"width1", "N·m", defaults_[2], 1e-3, 2.0, 0.1},
            {"width2", "N·m", defaults_[3], 1e-3, 2.0, 0.1}};
  }

  /// The steady state is the dead-zone deflection, so it is computed there.
  template <typename T>
  Vec2<T> operator()(const T* p, const JointState<T>& state) const {
    return BacklashDeadZoneEffect()(p, state);
  }

 private:
  double defaults_[4];
};

}  // namespace pliant::models
