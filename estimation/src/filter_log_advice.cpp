// What `pliant filter` advises about the parameters it was given for a log
// (filter_log.h).
#include <algorithm>
#include <string>

#include "pliant/estimation/filter_log.h"
#include "pliant/estimation/free_motion_fit.h"

namespace pliant::estimation {

std::string ArmDynamicsAdvice(const models::ModelParameters& parameters,
                              const FilterOptions& used, const io::LogHeader& header) {
  if (header.Has("tip_fixed") || used.quasi_static || !used.infer_contact) return "";
  const bool known = std::any_of(parameters.effects.begin(), parameters.effects.end(),
                                 [](const models::EffectParameters& e) {
                                   return FittedFromFreeMotion(e.name);
                                 });
  if (known) return "";
  return "the parameters hold none of the arm's own dynamics (joint_inertia, joint_friction): "
         "the filter learns the moving arm's torque from generic priors, which take up part of "
         "a push's first load and believe the push later — add a log of this arm moving freely "
         "to its identification (pliant identify LOGS… FREE.csv --effect joint_inertia --effect "
         "joint_friction -o PARAMS.json)";
}

}  // namespace pliant::estimation
