// The --json summary of a diagnosis: the fields first, in its order.
#include <cmath>

#include "diagnosis_report_internal.h"
#include "pliant/estimation/effect_catalogue.h"
#include "pliant/experiments/diagnosis_report.h"

namespace pliant::experiments {

bool detail::AtBound(const std::string& effect, const std::string& parameter, double value) {
  const auto& catalogue = estimation::EffectCatalogue::Global();
  if (!catalogue.Contains(effect)) return false;
  for (const auto& spec : catalogue.Create(effect)->Parameters()) {
    if (spec.name != parameter) continue;
    const double tolerance = 1e-6 * (spec.upper_bound - spec.lower_bound);
    return std::abs(value - spec.lower_bound) <= tolerance ||
           std::abs(value - spec.upper_bound) <= tolerance;
  }
  return false;
}

std::string detail::NisVerdict(const estimation::ResidualStatistics& s) {
  if (!(s.nis_band[1] > 0.0)) return "not computed";
  if (s.mean_nis > s.nis_band[1])
    return "above its band: the filter's errors are larger than its noise model allows — the "
           "model lacks something, or the noise settings are too small";
  if (s.mean_nis < s.nis_band[0])
    return "below its band: the filter's noise model is pessimistic (its σ are wider than the "
           "errors), not a sign of a missing effect";
  return "inside its band: the filter's noise model fits these rows";
}

namespace {

using Json = nlohmann::ordered_json;

Json Statistics(const estimation::ResidualStatistics& s) {
  return Json{{"samples", s.samples},
              {"rms_mm", s.rms_mm},
              {"rms_rad", {s.rms_rad[0], s.rms_rad[1]}},
              {"bias_rad", {s.bias_rad[0], s.bias_rad[1]}},
              {"mean_nis", s.mean_nis},
              {"nis_band", {s.nis_band[0], s.nis_band[1]}},
              {"ljung_box_q", s.ljung_box_q},
              {"ljung_box_p", s.ljung_box_p},
              {"normality_statistic", s.normality_statistic},
              {"normality_p", s.normality_p},
              {"nis_verdict", detail::NisVerdict(s)}};
}

Json Effect(const estimation::EffectFinding& e) {
  Json parameters = Json::array();
  for (std::size_t i = 0; i < e.parameter_names.size(); ++i) {
    parameters.push_back(
        {{"name", e.parameter_names[i]},
         {"value", i < e.parameters.size() ? Json(e.parameters[i]) : Json(nullptr)},
         {"sd", i < e.parameter_sd.size() ? Json(e.parameter_sd[i]) : Json(nullptr)},
         {"at_bound", i < e.parameters.size() &&
                          detail::AtBound(e.name, e.parameter_names[i], e.parameters[i])}});
  }
  return Json{{"name", e.name},
              {"description", e.description},
              {"channels", e.channels},
              {"score", e.score},
              {"p_value", e.p_value},
              {"size", e.size},
              {"size_sd", e.size_sd},
              {"size_unit", e.size_unit},
              {"missing", e.missing},
              {"delta_aic", e.delta_aic},
              {"delta_bic", e.delta_bic},
              {"heldout_rms_before_mm", e.heldout_rms_before_mm},
              {"heldout_rms_after_mm", e.heldout_rms_after_mm},
              {"unique_score", e.unique_score},
              {"indistinguishable_from", e.indistinguishable_from},
              {"separating_experiment", e.separating_experiment},
              {"parameters", parameters}};
}

Json Channel(const estimation::ChannelFinding& c) {
  return Json{{"name", c.name},       {"lag", c.lag},         {"score", c.score},
              {"joint", c.joint},     {"p_value", c.p_value}, {"finding", c.finding},
              {"remark", c.remark}};
}

}  // namespace

nlohmann::ordered_json DiagnosisSummaryJson(const estimation::Diagnosis& d) {
  Json effects = Json::array();
  for (const auto& e : d.effects) effects.push_back(Effect(e));
  Json channels = Json::array();
  for (const auto& c : d.channels) channels.push_back(Channel(c));
  Json added = Json::array();
  for (const auto& e : d.added) added.push_back(Effect(e));
  return Json{{"rms_before", d.rms_before_mm},
              {"rms_after", d.rms_after_mm},
              {"missing_effect", d.missing_effect ? Json(*d.missing_effect) : Json(nullptr)},
              {"effects", effects},
              {"channels", channels},
              {"rms_unit", "mm"},
              {"rms_recalibrated", d.rms_recalibrated_mm},
              {"noise_floor", d.noise_floor_mm},
              {"reference", d.reference},
              {"added_effects", d.added_effects},
              {"added", added},
              {"selected", d.selected},
              {"notes", d.notes},
              {"joints_recorded", {d.joint_recorded[0], d.joint_recorded[1]}},
              {"before", Statistics(d.before)},
              {"after", Statistics(d.after)}};
}

}  // namespace pliant::experiments
