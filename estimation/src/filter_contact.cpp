// Contact as the exception (FilterOptions::infer_contact): without the
// tip_fixed hint the external load is either 0 (no contact) or a slab
// N(·, σ_c²) (contact), switching as a two-state Markov chain. The filter
// keeps one Gaussian: before the effort update the slab's onset widens the
// load's variance (the IMM mixing of the chain), the update is the slab's,
// and after it the two hypotheses are collapsed into their mean and
// covariance (GPB1). docs/decisions/contact-prior.md says why.
#include <algorithm>
#include <cmath>

#include <Eigen/Cholesky>

#include "filter_impl.h"

namespace pliant::estimation::filter_internal {
namespace {

// log(e^a + e^b), −inf when both are.
double LogSumExp(double a, double b) {
  const double top = std::max(a, b);
  if (!std::isfinite(top)) return top;
  return top + std::log(std::exp(a - top) + std::exp(b - top));
}

// The chain's chances of a contact starting and of one ending over a step.
// A quasi-static log's t is a pose index, and no time passes in the chain
// between two poses but one nominal period's: a contact goes on from pose to
// pose unless the rows say otherwise (QuasiStaticTransitions).
struct ChainSwitch {
  double start, end;
};
ChainSwitch SwitchOver(const FilterOptions& o, const ContactRates& rates, double dt) {
  if (o.quasi_static) dt = o.sample_period_s;
  return {-std::expm1(-rates.start_hz() * dt), -std::expm1(-rates.end_hz() * dt)};
}

// The options' rates weigh as one episode of each kind: from its second
// contact on, a log's own episodes outweigh them.
constexpr double kPriorEpisodes = 1.0;
// An episode is counted once the chain believes it (p above 0.9) and ends
// once it believes the tip free again (below 0.1): the posterior's flicker
// inside a push or a free stretch is no new episode.
constexpr double kBelievedContact = 0.9, kBelievedFree = 0.1;

}  // namespace

void ContactRates::Start(const FilterOptions& o) {
  onsets_ = ends_ = free_s_ = contact_s_ = 0.0;
  believed_ = false;
  start_hz_ = o.contact_start_rate_hz;
  end_hz_ = o.contact_end_rate_hz;
}

// The Gamma posterior's mean, episodes over time at risk. The counts forget
// by 1 − dt/memory a step (first order: a step is milliseconds, the memory a
// minute; a longer step forgets all).
void ContactRates::Learn(const FilterOptions& o, double probability, double chain_dt_s) {
  // A quasi-static log's t is a pose index: no time to count rates in.
  if (!o.learn_contact_rates || o.quasi_static || !(chain_dt_s > 0.0) ||
      !std::isfinite(probability)) {
    return;
  }
  const double p = std::clamp(probability, 0.0, 1.0);
  const double keep = std::max(0.0, 1.0 - chain_dt_s / o.contact_rate_memory_s);
  onsets_ *= keep, ends_ *= keep, free_s_ *= keep, contact_s_ *= keep;
  free_s_ += (1.0 - p) * chain_dt_s;
  contact_s_ += p * chain_dt_s;
  if (!believed_ && p > kBelievedContact) {
    believed_ = true;
    onsets_ += 1.0;
  } else if (believed_ && p < kBelievedFree) {
    believed_ = false;
    ends_ += 1.0;
  }
  start_hz_ = (kPriorEpisodes + onsets_) / (kPriorEpisodes / o.contact_start_rate_hz + free_s_);
  end_hz_ = (kPriorEpisodes + ends_) / (kPriorEpisodes / o.contact_end_rate_hz + contact_s_);
}

ContactPrior MixContact(const FilterOptions& o, const ContactRates& rates, double probability,
                        double dt) {
  ContactPrior m;
  const ChainSwitch chance = SwitchOver(o, rates, dt);
  const double stays = probability * (1.0 - chance.end);
  m.probability = stays + (1.0 - probability) * chance.start;
  m.continuing = m.probability > 0.0 ? stays / m.probability : 0.0;
  const double ends = probability * chance.end;
  m.ended = m.probability < 1.0 ? ends / (1.0 - m.probability) : 0.0;
  return m;
}

double ContactLogLikelihoodRatio(double contact_innovation, double contact_variance,
                                 double free_residual, double free_variance, double free_dof,
                                 double held_log_evidence, double level_weight) {
  // Full log densities: the no-contact residual is Student-t when free_dof
  // is finite, and its normalisation differs from the Gaussian's.
  const double l1 = LogNormal(contact_innovation, contact_variance);
  double l0 = LogNormal(free_residual, free_variance);
  if (std::isfinite(free_dof)) {
    const double nu = free_dof;
    l0 = std::lgamma(0.5 * (nu + 1.0)) - std::lgamma(0.5 * nu) -
         0.5 * std::log(nu * 3.14159265358979323846 * free_variance) -
         0.5 * (nu + 1.0) * std::log1p(free_residual * free_residual / (nu * free_variance));
  }
  if (!(std::isfinite(l1) && std::isfinite(l0))) return 0.0;
  return std::clamp(level_weight * (l1 - l0) + held_log_evidence, -700.0, 700.0);
}

// The mixture of the slab posterior N(x, P) (weight p) and the same Gaussian
// conditioned on tau = 0 (weight 1 − p): with m = x_tau, g = P e_tau / P_tautau,
//   x+ = x − (1 − p)·m·g,   P+ = P − (1 − p)·(P_tautau − p·m²)·g gᵀ,
// a rank-one update (the conditioned branch is x − m·g, P − P_tautau·g gᵀ).
void CollapseContact(FilterJointState* state, double probability) {
  if (probability >= 1.0) return;
  Matrix& P = state->covariance;
  const double p_tau = P(kTorque, kTorque);
  if (!(p_tau > 0.0)) return;
  const double m = state->mean[kTorque];
  const Vector g = P.col(kTorque) / p_tau;
  state->mean -= (1.0 - probability) * m * g;
  P.noalias() -= ((1.0 - probability) * (p_tau - probability * m * m)) * (g * g.transpose());
}

// The held law of a pose pair: the encoder's travel either all bends the
// shaft (the load changes by h) or, with even odds, a share of it crosses
// the clearance first, no more than the travel nor the clearance's width 2δ
// (`crossable`, as a load): the change lies evenly between h and h less that.
// A still joint can cross nothing, and its held law is the free one.
namespace {
double HeldPairLogLikelihood(double residual_change, double h, double variance,
                             double crossable_nm) {
  const double bend = LogNormal(residual_change - h, variance);
  if (!(crossable_nm > 1e-9)) return bend;
  const double sd = std::sqrt(variance);
  const double low = h - std::copysign(crossable_nm, h);
  const double upper = (residual_change - std::min(h, low)) / sd;
  const double lower = (residual_change - std::max(h, low)) / sd;
  // Φ(upper) − Φ(lower) through erfc, exact in the tails.
  const double mass =
      0.5 * (std::erfc(-upper / std::sqrt(2.0)) - std::erfc(-lower / std::sqrt(2.0)));
  const double cross = std::log(std::max(mass, 1e-300)) - std::log(crossable_nm);
  return LogSumExp(bend, cross) + std::log(0.5);
}
}  // namespace

// Two consecutive poses of one depth in a quasi-static log, r the effort
// residual and h = Δq/(s·K(L)) the load the encoder's travel would add to a
// held shaft. The chain moves between them in one of four ways, each with its
// own law for this pose's residual given the last's:
//   held    (contact → contact): r − r_prev = h, the shaft bent by the travel;
//   free    (free → free):       r − r_prev = 0, the bias table's error stays
//                                between two nearby poses;
//   onset   (free → contact):    r − r_prev is a new load from the slab;
//   release (contact → free):    r is the table's error alone, N(0, free).
// What changes besides (the held friction) the model takes out under all.
// Each sees the two poses' effort noise (noise_rows·σ_e²: 1/n of a window
// mean of n rows, white as the Kalman update takes it); the held one also
// the doubt of s and the clearance, which the travel may cross instead of
// bending the shaft (HeldPairLogLikelihood).
// Only the onset and the release score the residual's size: a contact that
// goes on is judged by whether its load follows the encoder, so a clamp's
// load passing through zero stays a contact.
PoseTransitions QuasiStaticTransitions(const FilterOptions& o, double residual,
                                       double residual_change, double encoder_change,
                                       double scale_compliance, double scale_sd,
                                       double clearance_rad, double internal_torque_change,
                                       double free_variance, double noise_rows) {
  PoseTransitions t;
  if (!(scale_compliance > 0.0) || !std::isfinite(residual_change) ||
      !std::isfinite(encoder_change) || !std::isfinite(residual)) {
    return t;
  }
  const double h = encoder_change / scale_compliance;
  const double noise = noise_rows * o.effort_noise_nm * o.effort_noise_nm +
                       internal_torque_change * internal_torque_change;
  const double model = scale_sd * scale_sd + o.deflection_model_error * o.deflection_model_error;
  const double sd_c = o.contact_load_sd_nm;
  t.valid = true;
  t.held = HeldPairLogLikelihood(residual_change, h, noise + model * h * h,
                                 std::min(std::abs(encoder_change), 2.0 * clearance_rad) /
                                     scale_compliance);
  t.free = LogNormal(residual_change, noise);
  t.onset = LogNormal(residual_change, noise + sd_c * sd_c);
  t.release = LogNormal(residual, free_variance);
  return t;
}

bool PairWindow::Add(const LastPose& row, double time_s, double min_travel_rad,
                     LastPose* closed) {
  if (!row.valid || !std::isfinite(time_s)) {
    Restart();
    return false;
  }
  if (rows > 0 && std::abs(row.depth_m - sum.depth_m) > kMaxHeldDepthChange) Restart();
  if (rows == 0) {
    sum = row;
    start_s = time_s;
    first_encoder_rad = row.encoder_rad;
  } else {
    sum.encoder_rad += row.encoder_rad;
    sum.residual_nm += row.residual_nm;
    sum.internal_torque_nm += row.internal_torque_nm;
    sum.arm_regressor += row.arm_regressor;
  }
  ++rows;
  const double elapsed = time_s - start_s;
  if (elapsed < kPairWindowS) return false;
  if (std::abs(row.encoder_rad - first_encoder_rad) < min_travel_rad && elapsed < kMaxPairWindowS) {
    return false;
  }
  closed_duration_s = elapsed;
  LastPose mean = sum;
  mean.encoder_rad /= rows, mean.residual_nm /= rows, mean.internal_torque_nm /= rows;
  mean.arm_regressor /= rows;
  mean.rows = rows;
  rows = 0;
  const bool pair =
      previous.valid && std::abs(mean.depth_m - previous.depth_m) <= kMaxHeldDepthChange;
  *closed = mean;
  if (!pair) previous = mean;
  return pair;
}

double HeldWindowEvidence(const PoseTransitions& t) {
  if (!t.valid) return 0.0;
  return LogSumExp(t.held - t.free, 0.0) + std::log(0.5);
}

double ContactAfterPosePair(const FilterOptions& o, const ContactRates& rates, double probability,
                            const PoseTransitions& evidence) {
  const ChainSwitch chance = SwitchOver(o, rates, o.sample_period_s);  // one period per pose
  const double p = std::clamp(probability, 0.0, 1.0);
  // log(0) is −inf: a move the last pose rules out adds nothing.
  const double contact =
      LogSumExp(std::log(p) + std::log1p(-chance.end) + evidence.held,
                std::log1p(-p) + std::log(chance.start) + evidence.onset);
  const double free = LogSumExp(std::log(p) + std::log(chance.end) + evidence.release,
                                std::log1p(-p) + std::log1p(-chance.start) + evidence.free);
  if (!std::isfinite(contact)) return 0.0;
  if (!std::isfinite(free)) return 1.0;
  return 1.0 / (1.0 + std::exp(std::clamp(free - contact, -700.0, 700.0)));
}

// 50 ms: the effort's noise through s·K(L) (≈ 0.5 mrad a sample at 0.01 N·m)
// leaves the fitted speed a few mrad/s at 100-1500 Hz, well below the speed
// from which an arm counts as moving (unmodelled_effort_speed_rad_s).
constexpr double kFreeMotionTimeS = 0.05;

void FreeArmMotion::Advance(double dt, double z_rad) {
  if (!std::isfinite(z_rad)) return;
  this->z_rad = z_rad;
  if (!(dt > 0.0)) return;
  if (!started) {
    started = true;
    level_rad = z_rad;
    velocity_rad_s = 0.0;
    return;
  }
  if (dt != theta_dt_s) {
    theta_dt_s = dt;
    theta = std::exp(-dt / kFreeMotionTimeS);
  }
  level_rad += velocity_rad_s * dt;
  const double residual = z_rad - level_rad;
  level_rad += (1.0 - theta * theta) * residual;
  velocity_rad_s += (1.0 - theta) * (1.0 - theta) / dt * residual;
}

void UnmodelledEffort::Learn(double weight, double residual, double rest_variance) {
  // Winsorised at 3σ of the no-contact residual, so that a contact the chain
  // has not yet recognised does not inflate it.
  const double total = rest_variance + variance;
  const double r2 = std::min(residual * residual, 9.0 * total);
  variance += weight * (std::max(0.0, r2 - rest_variance) - variance);
}

}  // namespace pliant::estimation::filter_internal
