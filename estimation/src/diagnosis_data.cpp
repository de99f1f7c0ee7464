// Which rows of a log the diagnosis compares, against what reference, and
// what each row's effects read (docs/diagnose-method.md).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "diagnosis_internal.h"
#include "pliant/io/file_checksum.h"
#include "pliant/io/input_error.h"
#include "pliant/estimation/effect_inputs.h"
#include "pliant/estimation/extra_effects.h"
#include "pliant/models/psm_kinematics.h"

namespace pliant::estimation::diagnosis {
namespace {

// Fewer compared samples than this cannot be cross-validated or fitted.
constexpr std::size_t kMinimumSamples = 20;

models::BacklashDeadZoneEffect DeadZoneOf(const models::ModelParameters& p) {
  return models::BacklashDeadZoneEffect(p.joints[0].backlash_rad, p.joints[1].backlash_rad,
                                        ClearanceLoad(p.joints[0]), ClearanceLoad(p.joints[1]));
}

// A column that exists and holds a value in at least one row.
bool HasValues(const io::Log& log, int column) {
  if (column < 0) return false;
  for (std::size_t r = 0; r < log.Rows(); ++r) {
    if (std::isfinite(log.Value(r, column))) return true;
  }
  return false;
}

// A reference pair is usable when it holds values for every recorded joint.
bool HasPair(const io::Log& log, int c1, int c2, const bool recorded[2]) {
  return (!recorded[0] || HasValues(log, c1)) && (!recorded[1] || HasValues(log, c2)) &&
         (HasValues(log, c1) || HasValues(log, c2));
}

std::string ChooseReference(const io::Log& log, const io::StandardColumns& c,
                            const std::string& wanted, const std::string& log_path,
                            const bool recorded[2]) {
  const bool has_ref = HasPair(log, c.q1_ref, c.q2_ref, recorded);
  const bool has_true = HasPair(log, c.q1_true, c.q2_true, recorded);
  bool has_fixed = false;
  if (c.tip_fixed >= 0) {
    for (std::size_t r = 0; r < log.Rows() && !has_fixed; ++r)
      has_fixed = log.Value(r, c.tip_fixed) > 0.5;
  }
  const std::string fix = "log the tip held still (tip_fixed = 1 with a segment number) or fill "
                          "q1_ref, q2_ref from a tracker";
  if (wanted == "auto") {
    if (has_ref) return "q*_ref";
    if (has_fixed) return "tip_fixed";
    if (has_true) return "q*_true";
    const bool empty_ref = c.q1_ref >= 0 || c.q2_ref >= 0;
    throw io::InputError(log_path, 0, 0,
                         std::string("the log says nowhere where the tip was (no tip_fixed rows, ") +
                             (empty_ref ? "q1_ref/q2_ref columns without values)"
                                        : "no q1_ref/q2_ref)"),
                         fix);
  }
  const bool available = (wanted == "q*_ref" && has_ref) || (wanted == "tip_fixed" && has_fixed) ||
                         (wanted == "q*_true" && has_true);
  if (!available) {
    throw io::InputError(log_path, 0, 0,
                         "the log has no " + wanted + " reference (the columns are missing or "
                         "hold no value)",
                         "use --reference auto, or " + fix);
  }
  return wanted;
}

}  // namespace

double ClearanceLoad(const models::JointParameters& joint) {
  // Below a few times this load the shaft's place in the clearance has memory
  // the model lacks.
  return std::max({joint.deadzone_width_nm, joint.tau_min_nm, 0.05});
}

BaseModel::BaseModel(const models::ModelParameters& parameters,
                     const std::vector<std::string>& refitted)
    : parameters_(parameters),
      compliance_(parameters.joints[0], parameters.joints[1]),
      deadzone_(DeadZoneOf(parameters)) {
  const ExtraEffects effects(parameters.effects);
  for (std::size_t i = 0; i < effects.models().size(); ++i) {
    const std::string name(effects.models()[i]->Info().name);
    if (std::find(refitted.begin(), refitted.end(), name) != refitted.end()) continue;
    file_effects_.push_back(MakeTerm(name));
    file_effects_.back().parameters = effects.values()[i];
    file_jets_.emplace_back(effects.values()[i].begin(), effects.values()[i].end());
  }
  for (const auto& joint : parameters.joints) {
    compliance_values_.insert(compliance_values_.end(), joint.compliance.cubic.coefficients.begin(),
                              joint.compliance.cubic.coefficients.end());
  }
  for (int j = 0; j < 2; ++j) {
    deadzone_values_[j] = parameters.joints[j].backlash_rad;
    deadzone_values_[2 + j] = ClearanceLoad(parameters.joints[j]);
    clearance_load_nm_[j] = compared_load_nm_[j] = deadzone_values_[2 + j];
  }
}

namespace {

// Which joints the log records: a joint whose angle or effort column holds no
// value in any row was not recorded (docs/log-format.md, one-joint logs).
void FindRecordedJoints(const io::Log& log, const io::StandardColumns& c, bool recorded[2]) {
  recorded[0] = log.header.JointRecorded(1) && HasValues(log, c.q1) && HasValues(log, c.tau1);
  recorded[1] = log.header.JointRecorded(2) && HasValues(log, c.q2) && HasValues(log, c.tau2);
}

// Row r through `effect_rows`; an unrecorded joint stays at rest at 0 (its
// prior): nothing is read from it.
models::JointState<double> StreamRow(const io::Log& log, const io::StandardColumns& c,
                                     const Problem& problem, std::size_t r,
                                     EffectInputs& effect_rows) {
  models::JointState<double> state = effect_rows.Update(c, &log.values[r * log.Columns()]);
  for (int j = 0; j < 2; ++j) {
    if (problem.joint_recorded[j]) continue;
    state.encoder_angle_rad[j] = state.velocity_rad_s[j] = state.effort_rate_nm_s[j] = 0.0;
    state.travel_since_reversal_rad[j] = state.acceleration_rad_s2[j] = 0.0;
  }
  return state;
}

struct RowInputs {
  double effort_rate_window_s = 0.1;
  std::vector<Eigen::Vector2d> centred_rate, centred_acceleration;  // empty: quasi-static
  int ref[2] = {-1, -1};
};

// The compared samples with their loads beyond `load_factor` × the clearance
// load; `group_of_segment` and `tip_group_of_run` receive the groups seen.
std::vector<Sample> CollectSamples(const io::Log& log, const io::StandardColumns& c,
                                   const Problem& problem, const BaseModel& model,
                                   const std::vector<Term>& added, const DiagnoseOptions& options,
                                   const RowInputs& in, double load_factor,
                                   std::map<long, int>& group_of_segment,
                                   std::map<int, int>& tip_group_of_run) {
  const auto& joints = model.parameters().joints;
  std::vector<const double*> values;
  for (const Term& term : added) values.push_back(term.parameters.data());
  const int tau[2] = {c.tau1, c.tau2};
  std::vector<Sample> all;
  int run = -1;
  bool previous_kept = false;
  // What the effects read of each row (velocity, travel since reversal, time),
  // fed every row (kept or not) through the one tracker that pliant correct
  // and the filter stream a log with: an effect is fitted here on the inputs
  // it will meet there; the effort's rate is the same line, centred.
  EffectInputs effect_rows(problem.quasi_static, kTimeGapS, in.effort_rate_window_s);
  for (std::size_t r = 0; r < log.Rows(); ++r) {
    const models::JointState<double> inputs = StreamRow(log, c, problem, r, effect_rows);
    const bool fixed = c.tip_fixed >= 0 && log.Value(r, c.tip_fixed) > 0.5;
    const bool keep = problem.profile_tip ? fixed : (c.tip_fixed < 0 || fixed);
    if (keep && !previous_kept) ++run;
    previous_kept = keep;
    if (!keep) continue;
    Sample s;
    s.row = r;
    s.state = inputs;
    s.state.compliance_rad_per_nm = models::CompliancesAt(joints, s.state.insertion_depth_m);
    Eigen::Vector2d effort(0.0, 0.0);
    // An unrecorded joint stays at rest at 0 (its prior): nothing is read from it.
    for (int j = 0; j < 2; ++j) {
      if (!problem.joint_recorded[j]) continue;
      if (!in.centred_rate.empty()) {
        s.state.effort_rate_nm_s[j] = in.centred_rate[r][j];
        s.state.acceleration_rad_s2[j] = in.centred_acceleration[r][j];
      }
      effort[j] = log.Value(r, tau[j]);
      if (!problem.profile_tip) s.reference_rad[j] = log.Value(r, in.ref[j]);
    }
    if (!s.state.encoder_angle_rad.allFinite() || !std::isfinite(s.state.insertion_depth_m) ||
        !effort.allFinite() || !s.reference_rad.allFinite())
      continue;
    for (int j = 0; j < 2; ++j) {
      s.state.external_torque_nm[j] =
          problem.joint_recorded[j]
              ? effort[j] - models::BiasTorqueAt(joints[j], s.state.encoder_angle_rad[j],
                                                 s.state.insertion_depth_m)
              : 0.0;
    }
    models::JointState<double> loaded = s.state;
    model.TakeOutInternalTorque(&loaded);
    for (std::size_t i = 0; i < added.size(); ++i) {
      if (added[i].effect->Info().channel == models::Channel::kInternalTorque)
        loaded.external_torque_nm -= added[i].effect->Evaluate(values[i], loaded);
    }
    for (int j = 0; j < 2; ++j) {
      s.used[j] = problem.joint_recorded[j] &&
                  std::abs(loaded.external_torque_nm[j]) >
                      load_factor * model.compared_load_nm(j) &&
                  std::abs(effort[j]) < options.filter.effort_limit_nm;
    }
    if (!s.used[0] && !s.used[1]) continue;
    const long segment = c.segment >= 0 ? std::lround(log.Value(r, c.segment)) : run;
    s.group = group_of_segment.emplace(segment, int(group_of_segment.size())).first->second;
    s.tip_group = tip_group_of_run.emplace(run, int(tip_group_of_run.size())).first->second;
    const Eigen::Matrix2d to_mm = models::TipDisplacementJacobianMm(
        Eigen::Vector3d(s.state.encoder_angle_rad[0], s.state.encoder_angle_rad[1],
                        s.state.insertion_depth_m));
    s.mm_per_rad = to_mm.diagonal();
    all.push_back(s);
  }
  return all;
}

std::string Format(const char* format, double value) {
  char text[64];
  return std::string(text, std::min<int>(63, std::snprintf(text, sizeof text, format, value)));
}

}  // namespace

Problem BuildProblem(const io::Log& log, const std::string& log_path, const BaseModel& model,
                     const std::vector<Term>& added, const DiagnoseOptions& options) {
  const io::StandardColumns c(log.header);
  Problem problem;
  FindRecordedJoints(log, c, problem.joint_recorded);
  if (!problem.joint_recorded[0] && !problem.joint_recorded[1]) {
    throw io::InputError(log_path, 0, 0,
                         "neither joint 1 nor joint 2 is recorded (their q and tau columns hold "
                         "no value)",
                         "log q1, tau1 or q2, tau2");
  }
  for (int j = 0; j < 2; ++j) {
    if (!problem.joint_recorded[j]) {
      problem.notes.push_back("joint " + std::to_string(j + 1) +
                              " is not recorded in this log: only joint " +
                              std::to_string(2 - j) + " is diagnosed; joint " +
                              std::to_string(j + 1) + " stays at its prior (at rest, unloaded)");
    }
  }
  problem.reference =
      ChooseReference(log, c, options.reference, log_path, problem.joint_recorded);
  problem.profile_tip = problem.reference == "tip_fixed";
  RowInputs in;
  in.ref[0] = problem.reference == "q*_ref" ? c.q1_ref : c.q1_true;
  in.ref[1] = problem.reference == "q*_ref" ? c.q2_ref : c.q2_true;
  // A quasi-static log's t is a pose index: no velocity or effort rate is read from it.
  const bool quasi_static = log.header.QuasiStatic();
  problem.quasi_static = quasi_static;
  in.effort_rate_window_s = options.effort_rate_window_s;
  if (!quasi_static) {
    in.centred_rate = CentredEffortRates(log, options.effort_rate_window_s, kTimeGapS);
    in.centred_acceleration = CentredAccelerations(log, options.effort_rate_window_s, kTimeGapS);
  }
  if (quasi_static) {
    problem.notes.push_back("the log holds quasi-static means (# timing: quasi-static): no "
                            "velocity or effort rate is read from its t, so friction and an "
                            "effort delay cannot be identified from it, nor a drift in time");
  }

  // Rows loaded beyond the clearance; when the log pushes no joint that far,
  // the rows beyond it at all, then beyond half of it, saying so.
  std::map<long, int> group_of_segment;
  std::map<int, int> tip_group_of_run;
  std::vector<Sample> all;
  double factor = options.min_load_factor;
  for (double f : {options.min_load_factor, 1.0, 0.5}) {
    if (f > options.min_load_factor) continue;
    factor = f;
    group_of_segment.clear(), tip_group_of_run.clear();
    all = CollectSamples(log, c, problem, model, added, options, in, f, group_of_segment,
                         tip_group_of_run);
    if (all.size() >= kMinimumSamples) break;
  }
  if (all.empty()) {
    throw io::InputError(log_path, 0, 0,
                         "no row of the log has the tip where the reference says and a load on "
                         "a recorded joint beyond half the cannula clearance's load (" +
                             Format("%.3g", 0.5 * model.compared_load_nm(0)) + " / " +
                             Format("%.3g", 0.5 * model.compared_load_nm(1)) + " N·m)",
                         "log pushes of the held tip (tip_fixed = 1) or a tracker reference "
                         "while the joints are loaded");
  }
  if (factor < options.min_load_factor) {
    problem.notes.push_back(
        "no push in this log reaches " + Format("%.3g", options.min_load_factor) +
        " × the load that takes up the cannula clearance (" +
        Format("%.3g", options.min_load_factor * model.compared_load_nm(0)) + " / " +
        Format("%.3g", options.min_load_factor * model.compared_load_nm(1)) +
        " N·m on joint 1 / 2): rows beyond " + Format("%.3g", factor) +
        " × are compared instead. There the shaft's place in the clearance still depends on "
        "its history, so the clearance and effects of the clearance (backlash_depth) cannot "
        "be identified from this log; to identify them, push the held tip beyond those loads");
  }
  // A recorded joint that no compared row loads is not diagnosed at all: say
  // so, with the load it needed (a wide take-up width in the parameters
  // raises it beyond every push of the log).
  for (int j = 0; j < 2; ++j) {
    const bool compared = std::any_of(all.begin(), all.end(), [j](const Sample& s) { return s.used[j]; });
    if (!problem.joint_recorded[j] || compared) continue;
    // (Where the take-up probe will look from a clearance's take-up, say so.)
    const bool probed = added.empty() && options.probe_wide_take_up &&
                        model.clearance_load_nm(j) >
                            kWideTakeUpFactor * NarrowTakeUpNm(model.parameters().joints[j]);
    problem.notes.push_back(
        "joint " + std::to_string(j + 1) + " is not diagnosed" +
        (probed ? " at the parameters' take-up" : "") + ": no row loads it beyond " +
        Format("%.3g", factor * model.compared_load_nm(j)) + " N·m (" + Format("%.3g", factor) +
        " × the parameters' clearance load, the largest of its dead-zone width " +
        Format("%.3g", model.parameters().joints[j].deadzone_width_nm) + " N·m, tau_min and " +
        "0.05 N·m); " +
        (probed ? "the take-up probe compares it from a clearance's take-up (its note follows)"
                : "push it further, or check a dead-zone width wider than the clearance's "
                  "take-up (an identification can widen it to absorb a load effect)"));
  }
  // Thin evenly for speed (docs/diagnose-method.md: fitting on a subsample).
  const std::size_t stride =
      std::max<std::size_t>(1, (all.size() + options.max_samples - 1) / options.max_samples);
  for (std::size_t i = 0; i < all.size(); i += stride) problem.samples.push_back(all[i]);

  // Too few segments for the folds: cut each into consecutive parts (under
  // tip_fixed each part keeps its own tip angle, which stays valid).
  int groups = int(group_of_segment.size());
  const int wanted_folds = std::max(2, options.folds);
  if (groups < wanted_folds) {
    const int parts = (wanted_folds + groups - 1) / groups;
    std::vector<std::size_t> count(groups, 0), seen(groups, 0);
    for (const Sample& s : problem.samples) ++count[s.group];
    for (Sample& s : problem.samples) {
      const int part = int(seen[s.group]++ * parts / std::max<std::size_t>(1, count[s.group]));
      s.group = s.group * parts + part;
    }
    groups *= parts;
  }
  problem.groups = groups;
  problem.tip_groups = int(tip_group_of_run.size());
  problem.rms_window_s = options.rms_window_s;
  diagnosis::AssignFolds(wanted_folds, &problem);

  // Noise of the residual: effort noise through K(L) at the median depth,
  // encoder quantisation and the reference's own noise.
  std::vector<double> depths;
  for (const Sample& s : problem.samples) depths.push_back(s.state.insertion_depth_m);
  std::nth_element(depths.begin(), depths.begin() + depths.size() / 2, depths.end());
  const double reference_sd = problem.reference == "q*_ref" ? options.filter.reference_noise_rad : 0.0;
  const auto& joints = model.parameters().joints;
  for (int j = 0; j < 2; ++j) {
    const double k = models::ComplianceAt(joints[j], depths[depths.size() / 2]);
    problem.noise_sd_rad[j] = std::sqrt(std::pow(k * options.filter.effort_noise_nm, 2) +
                                        std::pow(options.filter.encoder_noise_rad, 2) +
                                        reference_sd * reference_sd);
  }
  return problem;
}

// Parameters identified on the log they diagnose have taken up what they
// could of any effect in it (the bias table's depth terms a drift in time on
// a log that visits its depths in order, K(L) and δ a stiffening): the
// residual shows only the rest, and a missing effect may read as none.
void NoteFittedOnThisLog(const models::ModelParameters& parameters, const std::string& log_path,
                         std::vector<std::string>* notes) {
  const auto log = io::FittedOn(parameters.identified_from, log_path);
  if (!log) return;
  notes->push_back("the parameters were fitted on this log (their identified_from: " + log->file +
                   ", the same CRC-32): what that fit took up of an effect leaves no residual "
                   "here, so an effect may be missed \u2014 diagnose against parameters "
                   "identified on a separate calibration log (pliant identify CALIBRATION.csv "
                   "-o P.json)");
}

}  // namespace pliant::estimation::diagnosis
