// One Monte Carlo trial (montecarlo_trial.h): simulate a divot push (or a
// clamped-beam sweep) of a drawn instrument, correct it five ways, score each
// against the simulator's truth.
#include <algorithm>
#include <cmath>
#include <string>
#include <stdexcept>

#include <Eigen/Dense>
#include <boost/math/distributions/lognormal.hpp>
#include <boost/math/distributions/normal.hpp>
#include <boost/math/distributions/uniform.hpp>

#include "pliant/estimation/compliance_correction.h"
#include "pliant/estimation/consistency.h"
#include "pliant/estimation/filter_log.h"
#include "pliant/estimation/filter_smoother.h"
#include "pliant/estimation/identification.h"
#include "pliant/estimation/joint_smoother.h"
#include "pliant/estimation/tip_error_statistics.h"
#include "pliant/experiments/montecarlo_trial.h"
#include "pliant/experiments/simulator.h"

namespace pliant::experiments {
namespace {

constexpr int kCoverageEvery = 15;  // 0.01 s at 1.5 kHz

// Identifies the trial's parameters on its calibration runs (paper's procedure).
models::ModelParameters Identify(const Study& study, const Truth& truth, const TrialDraw& draw,
                                 TrialStream& stream) {
  estimation::IdentificationData data;
  for (std::size_t i = 0; i < study.calibration.size(); ++i) {
    Scenario calibration = study.calibration[i];
    calibration.truth = truth;
    calibration.sensors.effort_noise_sd_nm = draw.values[kEffortNoiseSdNm];
    const auto result = Simulate(calibration, stream.Next());
    estimation::AppendSamples(result.log, calibration.name, {}, &data);
  }
  auto prior = NominalParameters(study, draw.values[kDepthM]);
  if (study.identify_method == Study::IdentifyMethod::kPaper) {
    return estimation::RunPaperProcedure(data, prior).parameters;
  }
  return estimation::RunJointSmoother(data, prior, estimation::JointSmootherOptions{}).parameters;
}

// How far a drawn quantity lies from the value the filter is given, as a
// root mean square: its standard deviation and its mean's distance from that
// value (the clamp to its physical range is ignored: it cuts far tails only).
// A lab knows how much its instruments vary, and about what.
double RmsAbout(const Distribution& d, double given) {
  double mean = d.a, sd = 0.0;
  if (d.Varies()) {
    switch (d.kind) {
      case Distribution::Kind::kUniform: {
        const boost::math::uniform u(d.a, d.b);
        mean = boost::math::mean(u), sd = boost::math::standard_deviation(u);
        break;
      }
      case Distribution::Kind::kNormal:
        mean = d.a, sd = d.b;
        break;
      case Distribution::Kind::kLogNormal: {
        const boost::math::lognormal l(std::log(d.a), d.b);
        mean = boost::math::mean(l), sd = boost::math::standard_deviation(l);
        break;
      }
      case Distribution::Kind::kConstant:
        break;
    }
  }
  return std::hypot(sd, mean - given);
}

// The filter's prior on the instrument: the study's spread about the nominal
// parameters, or what identification says where it gives a covariance (the
// filter reads it when the option is left NaN). The compliance scale keeps
// the filter's own allowance for the K(L) law when the spread is smaller.
void InstrumentPrior(const Study& study, const models::ModelParameters& parameters,
                     estimation::FilterOptions* options) {
  const auto& q = study.quantities;
  const auto identified = [&](const std::string& name) {
    return study.identify && std::isfinite(estimation::ParameterStandardDeviation(parameters, name));
  };
  if (!study.identify) {
    options->compliance_scale_sd = std::max({options->compliance_scale_sd,
                                             RmsAbout(q[kComplianceScale1], 1.0),
                                             RmsAbout(q[kComplianceScale2], 1.0)});
  }
  for (int j = 0; j < 2; ++j) {
    const std::string prefix = "joint" + std::to_string(j + 1) + ".";
    options->backlash_sd_rad[j] =
        identified(prefix + "backlash_rad")
            ? estimation::FilterOptions::kFromParameters
            : RmsAbout(q[kBacklash1Rad + j], parameters.joints[j].backlash_rad);
    options->effort_offset_sd_nm[j] = identified(prefix + "bias_torque.coefficients[0]")
                                          ? estimation::FilterOptions::kFromParameters
                                          : RmsAbout(q[kBiasOffset1Nm + j], 0.0);
  }
}

}  // namespace

const char* CorrectionMethodName(int method) {
  static const char* const kNames[kCorrectionMethods] = {"none", "equation2", "deadzone", "filter",
                                                         "smoother"};
  return kNames[method];
}

models::ModelParameters NominalParameters(const Study& study, double depth_m) {
  models::ModelParameters parameters = estimation::PaperPrior();
  const Truth& truth = study.scenario.truth;
  for (int j = 0; j < 2; ++j) {
    auto& joint = parameters.joints[j];
    const auto& nominal = truth.joints[j];
    joint.compliance = nominal.compliance;
    joint.backlash_rad = nominal.backlash_rad;
    joint.depth_min_m = nominal.depth_min_m;
    joint.depth_max_m = nominal.depth_max_m;
    joint.bias_form = models::BiasForm::kTable;
    joint.bias_torque = nominal.bias_torque;
    const double shift =
        truth.bias_depth_slope_nm_per_m[j] * (depth_m - truth.bias_reference_depth_m);
    for (double& v : joint.bias_torque.torque_nm) v += shift;
  }
  parameters.covariance.reset();
  return parameters;
}

Truth TrialTruth(const Study& study, const TrialDraw& draw) {
  Truth truth = study.scenario.truth;
  for (int j = 0; j < 2; ++j) {
    auto& joint = truth.joints[j];
    models::ScaleCompliance(joint.compliance, draw.values[kComplianceScale1 + j]);
    joint.backlash_rad = draw.values[kBacklash1Rad + j];
    for (double& v : joint.bias_torque.torque_nm) v += draw.values[kBiasOffset1Nm + j];
    // Inside the clearance: the scenario refuses a shaft that starts on a wall.
    truth.initial_shaft_offset_rad[j] =
        0.999 * std::clamp(draw.values[kShaftStart1 + j], -1.0, 1.0) * joint.backlash_rad;
  }
  return truth;
}

TrialResult RunTrial(const Study& study, int trial) {
  TrialStream stream(study.seed, static_cast<std::uint64_t>(trial));
  TrialResult out;
  out.trial = trial;
  out.draw = DrawTrial(study, stream);
  const TrialDraw& d = out.draw;

  Scenario push = study.scenario;
  push.truth = TrialTruth(study, d);
  push.sensors.effort_noise_sd_nm = d.values[kEffortNoiseSdNm];
  if (push.type == ExperimentType::kClampedBeam) {  // one depth, to the drawn effort limit
    push.clamped_beam.depths_m = {d.values[kDepthM]};
    push.clamped_beam.effort_limit_nm = d.values[kPeakTorqueNm];
  } else {
    push.divot.depths_m = {d.values[kDepthM]};
    push.divot.directions_deg = {d.values[kDirectionDeg]};
    push.divot.peak_torques_nm = {d.values[kPeakTorqueNm]};
    push.divot.speeds_rad_s = {d.values[kSpeedRadS]};
  }
  const io::Log log = Simulate(push, d.simulation_seed).log;

  models::ModelParameters parameters = study.identify ? Identify(study, push.truth, d, stream)
                                                     : NominalParameters(study, d.values[kDepthM]);
  // The arm's dynamics, identified once on its free motion (study.arm_calibration).
  parameters.effects.insert(parameters.effects.end(), study.arm_effects.begin(),
                            study.arm_effects.end());
  const estimation::ComplianceCorrector equation2(parameters, estimation::CorrectionModel::kPaper);
  const estimation::ComplianceCorrector deadzone(parameters, estimation::CorrectionModel::kDeadZone);
  estimation::FilterOptions options;
  options.effort_noise_nm = std::max(d.values[kEffortNoiseSdNm], 1e-4);
  // The arm's motor inertia is a property of the PSM, not of the instrument
  // under study: the filter is told it (docs/filter.md, motor inertia), as a
  // lab would from the arm's dynamic identification; likewise the damping of
  // the instrument model's shaft, which the study does not vary.
  // (Identified, the file's joint_inertia carries it: not twice.)
  if (study.arm_effects.empty()) options.motor_inertia_kg_m2 = push.joint.inertia_kg_m2.mean();
  options.shaft_damping_nm_s_per_rad = push.tip.shaft_damping_nm_s_per_rad;  // the arm's shafts
  InstrumentPrior(study, parameters, &options);
  options.deflection_model_error = study.deflection_model_error;  // NaN: the filter's default
  options.load_follows_motor = study.load_follows_motor;
  options.infer_contact = study.infer_contact;
  options.unloaded_start_s = study.unloaded_start_s;
  if (std::isfinite(study.inertial_torque_error)) {
    options.inertial_torque_error = study.inertial_torque_error;
  }
  // The learned arm torque's prior σ, where the study sets them.
  const auto prior = [](double set, double* option) {
    if (std::isfinite(set)) *option = set;
  };
  prior(study.internal_inertia_sd_kg_m2, &options.internal_inertia_sd_kg_m2);
  prior(study.internal_coulomb_sd_nm, &options.internal_coulomb_sd_nm);
  prior(study.internal_viscous_sd_nm_s, &options.internal_viscous_sd_nm_s);
  estimation::FilterSmoother smoother(parameters, options);

  const io::StandardColumns c(log.header);
  if (c.q1_true < 0 || c.tip_fixed < 0) throw std::runtime_error("simulated log lacks truth columns");
  const std::size_t rows = log.Rows(), cols = log.Columns();
  smoother.Reserve(rows);
  for (std::size_t r = 0; r < rows; ++r) out.held_samples += log.values[r * cols + c.tip_fixed] != 0.0;
  if (out.held_samples == 0) throw std::runtime_error("the simulated push never held the tip");
  const long picked = std::min<long>(out.held_samples - 1, long(d.nees_pick * out.held_samples));

  estimation::TipErrorStatistics error[kCorrectionMethods];
  // Per estimator (0 filter, 1 smoother): the picked held sample, and every
  // kCoverageEvery-th held sample.
  estimation::ConsistencyTally picked_sample[2], every_kth[2];
  long held = 0;
  const auto score = [&](int estimator, const Eigen::Vector2d& error_rad,
                         const Eigen::Matrix2d& covariance_rad2) {
    if (held == picked) picked_sample[estimator].Add(error_rad, covariance_rad2);
    if (held % kCoverageEvery == 0) every_kth[estimator].Add(error_rad, covariance_rad2);
  };
  for (std::size_t r = 0; r < rows; ++r) {
    const double* v = &log.values[r * cols];
    auto sample = estimation::SampleFromRow(c, v, options.fuse_log_reference);
    const bool tip_held = sample.tip_fixed;  // the truth: scored on held rows either way
    sample.tip_fixed = tip_held && study.tip_fixed_hint;
    const auto filtered = smoother.Add(sample);
    if (!tip_held) continue;
    const Eigen::Vector3d q(v[c.q1], v[c.q2], v[c.q3]);
    const Eigen::Vector2d truth(v[c.q1_true], v[c.q2_true]), effort(v[c.tau1], v[c.tau2]);
    const auto with_angles = [&](const Eigen::Vector2d& a) { return Eigen::Vector3d(a[0], a[1], q[2]); };
    error[kUncorrected].Add(q, truth);
    error[kEquation2].Add(with_angles(equation2.Correct(q, effort).corrected_rad), truth);
    error[kDeadZone].Add(with_angles(deadzone.Correct(q, effort).corrected_rad), truth);
    error[kFilter].Add(with_angles(filtered.corrected_rad), truth);
    score(0, filtered.corrected_rad - truth, filtered.covariance_rad2);
    ++held;
  }
  smoother.Smooth();
  held = 0;
  for (std::size_t r = 0; r < rows; ++r) {
    const double* v = &log.values[r * cols];
    if (v[c.tip_fixed] == 0.0) continue;
    const Eigen::Vector2d truth(v[c.q1_true], v[c.q2_true]);
    const auto smoothed = smoother.Estimate(r);
    error[kSmoother].Add(Eigen::Vector3d(smoothed.corrected_rad[0], smoothed.corrected_rad[1], v[c.q3]),
                         truth);
    score(1, smoothed.corrected_rad - truth, smoothed.covariance_rad2);
    ++held;
  }
  for (int m = 0; m < kCorrectionMethods; ++m) out.tip_error_mm[m] = error[m].RmsMm();
  for (int e = 0; e < 2; ++e) {
    out.nees[e] = picked_sample[e].MeanNees();  // one sample: its NEES
    out.covered[e] = int(picked_sample[e].covered[0] + picked_sample[e].covered[1]);
    out.coverage_fraction[e] = every_kth[e].PooledCoverageFraction();
    for (int j = 0; j < 2; ++j) out.joint_coverage_fraction[e][j] = every_kth[e].CoverageFraction(j);
  }
  return out;
}

}  // namespace pliant::experiments
