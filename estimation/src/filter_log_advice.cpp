// What `pliant filter` reads of a log's efforts and advises about the
// parameters it was given for it (filter_log.h).
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>

#include "pliant/estimation/effort_noise.h"
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

FilterOptions EffortNoiseForLog(FilterOptions options, const std::vector<double> effort_nm[2],
                                std::vector<std::string>* notes, std::vector<std::string>* advice) {
  if (options.quasi_static) return options;
  double estimate = 0.0;
  for (int j = 0; j < 2; ++j) {
    const double sd = options.joint_recorded[j] ? EffortNoiseFromSamples(effort_nm[j]) : 0.0;
    if (std::isfinite(sd)) estimate = std::max(estimate, sd);
  }
  if (!(estimate > options.effort_noise_nm)) return options;
  std::ostringstream note;
  note << std::setprecision(3) << "the efforts hold " << estimate
       << " N·m of white noise (their second differences over the log's first "
       << effort_nm[0].size() << " rows), above the assumed "
       << options.effort_noise_nm << " N·m: ";
  if (!options.effort_noise_from_log) {
    note << "--effort-noise-from-log uses it (docs/decisions/effort-noise.md)";
    advice->push_back(note.str());
    return options;
  }
  note << "used";
  notes->push_back(note.str());
  options.effort_noise_nm = estimate;
  return options;
}

FilterOptions EffortColourForLog(FilterOptions options, const std::vector<double>& times_s,
                                 const std::vector<double> encoder_rad[2],
                                 const std::vector<double> effort_nm[2],
                                 std::vector<std::string>* notes,
                                 std::vector<std::string>* advice) {
  if (options.quasi_static || times_s.empty()) return options;
  double period = MedianRowSpacing(times_s);
  if (!(period > 0.0)) period = options.sample_period_s;
  const auto still = StillStretches(times_s, encoder_rad);
  // β carries the colour only where nothing else is asked of it: a constant
  // offset's doubt, a tare or a reference would each need β's constant part.
  const bool free = (options.effort_offset_sd_nm.array() == 0.0).all() &&
                    !(options.effort_offset_correlation_s.array() < HUGE_VAL).any() &&
                    options.unloaded_start_s == 0.0 && !options.fuse_log_reference;
  for (int j = 0; j < 2; ++j) {
    if (!options.joint_recorded[j]) continue;
    const EffortNoiseColour c = EffortNoiseColourFromStill(effort_nm[j], still, period);
    if (!c.found) continue;
    std::ostringstream note;
    note << std::setprecision(3) << "joint " << j + 1 << "'s effort holds noise correlated over "
         << 1e3 * c.correlation_s << " ms (σ " << c.coloured_sd_nm << " N·m; white "
         << c.white_sd_nm << " N·m; from " << c.stretches << " still stretches): ";
    if (!free || !options.effort_colour_from_log) {
      note << "not carried (the effort offset β is in other use, or --no-effort-colour); "
              "--effort-offset-sd and --effort-offset-correlation carry it "
              "(docs/decisions/coloured-effort-noise.md)";
      advice->push_back(note.str());
      continue;
    }
    note << "carried as the effort offset β";
    notes->push_back(note.str());
    options.effort_offset_sd_nm[j] = c.coloured_sd_nm;
    options.effort_offset_correlation_s[j] = c.correlation_s;
  }
  return options;
}

}  // namespace pliant::estimation
