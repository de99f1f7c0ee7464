// The study's arm identified once on its own free motion (study.h,
// IdentifyArmDynamics): what a lab does before it trusts a filter online.
#include <string>
#include <vector>

#include "pliant/estimation/free_motion_fit.h"
#include "pliant/experiments/montecarlo_trial.h"
#include "pliant/experiments/simulator.h"
#include "pliant/experiments/study.h"

namespace pliant::experiments {

std::vector<models::EffectParameters> IdentifyArmDynamics(const Study& study) {
  if (study.arm_calibration.empty()) return {};
  Scenario arm = study.arm_calibration.front();
  arm.joint = study.scenario.joint;  // the same arm as every trial's
  // Its own stream: the trials' (TrialStream(seed, k)) never reach this far.
  TrialStream stream(study.seed, std::uint64_t(1) << 62);
  const io::Log log = Simulate(arm, stream.Next()).log;
  const std::vector<std::string> names = estimation::FreeMotionEffectNames();
  const models::ModelParameters nominal =
      NominalParameters(study, study.scenario.truth.bias_reference_depth_m);
  const auto fit = estimation::FitEffectsOnFreeMotion({{&log, arm.name}}, nominal, names);
  std::vector<models::EffectParameters> effects;
  for (const auto& f : fit.fitted.effects)
    effects.push_back({f.name, f.parameter_names, f.parameters, f.parameter_sd});
  return effects;
}

}  // namespace pliant::experiments
