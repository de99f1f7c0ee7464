// The contact chain's evidence on each step of the filter (filter_step.cpp):
// both joints' shared posterior, the pose pairs that say whether a load
// follows the encoder, and the chance that a contact holds the tip.
// docs/decisions/contact-prior.md and contact-pair-windows.md say why.
#include <algorithm>
#include <cmath>

#include "filter_impl.h"

namespace pliant::estimation {

using namespace filter_internal;

// Without the hint, the chance that the last step's contact holds the tip
// (0 in a quasi-static log, whose every row starts the tip anew, and where
// the load is known or every residual is load).
double ComplianceFilter::Impl::HeldShare(const FilterSample& sample, int j) const {
  if (!InfersContact(sample) || options.quasi_static) return 0.0;
  return contact_probability[j] * held_given_contact;
}

// One contact for the tip: the chain's prior (the same for both joints once
// they have shared a posterior) with both joints' evidence.
void ComplianceFilter::Impl::ShareContact() {
  double log_odds = 0.0;
  int scored = 0, joint_scored = 0;
  for (int j = 0; j < 2; ++j) {
    if (!pending[j].update || !pending[j].mixture) continue;
    log_odds += pending[j].log_likelihood_ratio;
    ++scored;
    joint_scored = j;
  }
  if (scored == 0) return;
  // A quasi-static pose pair on every scored joint: the chain's four moves
  // from the last pose's posterior (ContactAfterPosePair).
  filter_internal::PoseTransitions pair;
  pair.valid = options.quasi_static;
  for (int j = 0; j < 2 && pair.valid; ++j) {
    if (!pending[j].update || !pending[j].mixture) continue;
    const auto& t = pending[j].transitions;
    pair.valid = t.valid;
    pair.held += t.held, pair.onset += t.onset, pair.release += t.release, pair.free += t.free;
  }
  if (pair.valid) {
    const double shared =
        filter_internal::ContactAfterPosePair(options, contact_rates, contact_probability[joint_scored],
                                              pair);
    for (int j = 0; j < 2; ++j) {
      if (pending[j].update && pending[j].mixture) contact_probability[j] = shared;
    }
    return;
  }
  LearnHold();
  if (!options.quasi_static) log_odds = LevelEvidence(log_odds);
  const double prior = contact_prior[joint_scored];
  const double prior_log_odds = std::log(prior) - std::log1p(-prior);  // ±inf at 0 and 1
  const double shared =
      1.0 / (1.0 + std::exp(-std::clamp(prior_log_odds + log_odds, -700.0, 700.0)));
  for (int j = 0; j < 2; ++j) {
    if (pending[j].update && pending[j].mixture) contact_probability[j] = shared;
  }
  contact_rates.Learn(options, shared, chain_step_s);
}

// A continuous log's evidence for contact on this row: each joint's pair
// window, and, the arm settled, both joints' effort levels together: the
// free arm's residual (the table's error and noise) against a contact's load
// of any direction and scale (ContactLogDensity), weighted as one look per
// pair window. While a joint moves as a free arm, its unmodelled torque is
// heavy-tailed at every scale and each joint's slab (per_joint, the sum of
// their log-likelihood ratios) is kept: a light load is not told from it
// (docs/decisions/contact-scale-free-load.md).
double ComplianceFilter::Impl::LevelEvidence(double per_joint) const {
  double held = 0.0, free = 0.0, radius2 = 0.0, variance = 0.0, weight = 1.0;
  int joints = 0;
  for (int j = 0; j < 2; ++j) {
    const PendingEffort& e = pending[j];
    if (!e.update || !e.mixture) continue;
    if (e.moving > 0.5) return per_joint;
    held += e.held_evidence;
    free += filter_internal::LogNormal(e.residual, e.free_variance);
    radius2 += e.residual * e.residual;
    variance += e.free_variance;
    weight = std::min(weight, e.level_weight);
    ++joints;
  }
  variance /= joints;
  const double low = options.unmodelled_effort_sd_nm, high = options.effort_limit_nm;
  const double contact = filter_internal::ContactLogDensity(radius2, joints, low * low + variance,
                                                            high * high + variance);
  if (!(std::isfinite(contact) && std::isfinite(free))) return held;
  return std::clamp(weight * (contact - free) + held, -700.0, 700.0);
}

// A continuous log's pair windows, closed on this row, on whether a contact
// would hold the tip: the held law against the moving one (the free arm's),
// both joints' together; between windows the chance drifts toward even at
// the contact chain's end rate.
void ComplianceFilter::Impl::LearnHold() {
  double log_odds = 0.0;
  bool closed = false;
  for (int j = 0; j < 2; ++j) {
    const auto& t = pending[j].transitions;
    if (!pending[j].update || !pending[j].mixture || !t.valid) continue;
    log_odds += t.held - t.free;
    closed = true;
  }
  if (!closed) return;
  const double window_s =
      std::max(pair_window[0].closed_duration_s, pair_window[1].closed_duration_s);
  const double drift = -std::expm1(-contact_rates.end_hz() * window_s);
  const double h = held_given_contact * (1.0 - drift) + (1.0 - held_given_contact) * drift;
  held_given_contact =
      1.0 / (1.0 + std::exp(std::clamp(std::log1p(-h) - std::log(h) - log_odds, -700.0, 700.0)));
}

namespace {
// The variance of what the arm's own torque does between two poses: the
// further effects' change and the learned torque's doubt over the change of
// motion (its regressor's), which a pair of poses counts as noise.
double ArmTorqueChangeVariance(const LastPose& a, const LastPose& b, const InternalTorque& arm) {
  const InternalTorque::Vector4 change = a.arm_regressor - b.arm_regressor;
  const double internal = a.internal_torque_nm - b.internal_torque_nm;
  return internal * internal + change.dot(arm.covariance * change);
}
}  // namespace

// The encoder's travel a continuous log's pair window waits for: a bend of
// four standard deviations of the pair it would close with this row — the
// means' noise σ_e²(1/n + 1/n_previous) and the arm's torque change
// (ArmTorqueChangeVariance) — and never more than single rows' √2·σ_e:
// within a steady push the windows are short, across a change of motion (a
// push's start, a stepping motor's holds) long. A window younger than
// kPairWindowS cannot close, and its travel is not computed.
double ComplianceFilter::Impl::WindowTravel(int j, const LastPose& now, double time_s) {
  constexpr double kNoiseMultiple = 4.0;
  double sd = std::sqrt(2.0) * options.effort_noise_nm;
  const PairWindow& w = pair_window[j];
  if (w.previous.valid && now.valid && w.rows > 0 && time_s - w.start_s >= kPairWindowS) {
    LastPose closing;
    closing.rows = w.rows + 1.0;
    closing.arm_regressor = (w.sum.arm_regressor + now.arm_regressor) / closing.rows;
    closing.internal_torque_nm = (w.sum.internal_torque_nm + now.internal_torque_nm) / closing.rows;
    const LastPose& p = w.previous;
    const double variance =
        options.effort_noise_nm * options.effort_noise_nm * (1.0 / closing.rows + 1.0 / p.rows) +
        ArmTorqueChangeVariance(closing, p, internal_torque[j]);
    sd = std::min(sd, std::sqrt(variance));
  }
  return kNoiseMultiple * sd * std::abs(joint[j].mean[kScale] * ComplianceAtDepth(j));
}

// The evidence for contact from the encoder's travel and the effort's change
// (QuasiStaticTransitions) between this row and a quasi-static log's last
// pose, or between a continuous log's last two pair windows (PairWindow).
// The poses must be at one depth (a clamp re-made elsewhere starts anew) with
// both encoders read. The learned arm torque's doubt over the change of
// motion is noise.
filter_internal::PoseTransitions ComplianceFilter::Impl::PoseChangeEvidence(
    const FilterSample& sample, int j, double residual, double free_variance) {
  const double encoder = sample.encoder_rad[j];
  const InternalTorque& arm = internal_torque[j];
  const LastPose now{std::isfinite(encoder), encoder, residual, depth,
                     extra_internal_torque_nm[j], arm.regressor};
  LastPose& last = options.quasi_static ? last_pose[j] : pair_window[j].previous;
  LastPose pose = now;
  filter_internal::PoseTransitions evidence;
  const bool pair = options.quasi_static
                        ? last.valid && now.valid &&
                              std::abs(depth - last.depth_m) <= kMaxHeldDepthChange
                        : pair_window[j].Add(now, sample.time_s,
                                             WindowTravel(j, now, sample.time_s), &pose);
  if (pair) {
    const FilterJointState& s = joint[j];
    const double noise_rows = 1.0 / pose.rows + 1.0 / last.rows;
    const double arm_change = ArmTorqueChangeVariance(pose, last, arm);
    const double learned = options.quasi_static ? 0.0 : free_pair_change[j].variance_nm2();
    const double change = pose.residual_nm - last.residual_nm;
    const double travel = pose.encoder_rad - last.encoder_rad;
    evidence = QuasiStaticTransitions(options, pose.residual_nm, change, travel,
                                      s.mean[kScale] * ComplianceAtDepth(j),
                                      std::sqrt(s.covariance(kScale, kScale)), delta[j],
                                      std::sqrt(arm_change + learned), free_variance, noise_rows);
    if (!options.quasi_static && evidence.valid) {
      // A travel within the clearance could be a held tip's crossing at no load.
      const double free_share =
          std::abs(travel) > 2.0 * delta[j]
              ? 1.0 / (1.0 + std::exp(std::clamp(evidence.held - evidence.free, -700.0, 700.0)))
              : 0.0;
      const double sd_e = options.effort_noise_nm;
      free_pair_change[j].Offer(change, arm_change + sd_e * sd_e * noise_rows, free_share);
    }
  }
  if (options.quasi_static || pair) last = pose;
  return evidence;
}

// The effort's update of both branches (filter_impl.h, branch_gap). The
// contact prior is the last contact going on (share w1) or a new one from the
// free branch, the slab's onset in the covariance (ContactOnsetVariance); the
// free prior is the free branch going on or the last contact ending (share
// u): x_c,prior = x + (w1 − p)·D, x_f,prior = x + (u − p)·D (IMM's mixing).
// One covariance, each branch's P_w = P − E·Eᵀ: the same gain updates both
// means, and the free branch is then conditioned on tau = 0. The state
// becomes their mixture at the posterior p, moment-matched:
//   x = p·x_c + (1 − p)·x_f,  P = P_c − (1 − p)·P_c e_tau e_tauᵀ P_c / P_c,tautau + E·Eᵀ,
// D = x_c − x_f, E = √(p(1 − p))·D (with D = 0 before: the slab's collapse, CollapseContact).
void ComplianceFilter::Impl::UpdateEffortBranches(const FilterSample& sample, int j, bool unloaded,
                                                  StepTally* tally) {
  const PendingEffort& e = pending[j];
  FilterJointState& s = joint[j];
  Vector& gap = branch_gap[j];
  const double w1 = branch_continuing[j], p = contact_probability[j];
  const double to_contact = w1 - branch_last[j];  // x_c,prior − x
  s.mean += to_contact * gap;
  Matrix& P = s.covariance;
  const Vector& spread = branch_spread[j];
  // A pose's branches share the covariance of the likelier before the effort
  // (PredictPoseBranches): a held tip's, narrow. When the effort makes the
  // free tip the likelier, the free tip's: under the held tip's, a hold the
  // hint had made certain went on to a free pose that its encoder, gated out,
  // could not move (experiments/third_generator). Not the other way: a
  // contact the effort first recognises keeps the restarted tip's breadth
  // (with the held tip's, the clamp's crossing went 2.0 → 2.9 mrad,
  // FilterQuasiStaticContact.AClampKeepsItsTipThroughTheClearance).
  if (has_pose_other[j] && p < 0.5) {
    P = pose_other[j];
  } else {
    P.noalias() -= spread * spread.transpose();  // each branch's own: P_w
  }
  has_pose_other[j] = false;
  const Vector h = Vector::Unit(kTorque) + Vector::Unit(kOffset);
  ScalarUpdate(j, kEffortChannel, h, e.residual - to_contact * gap[kOffset] - s.mean[kTorque],
               e.variance, tally, false, ConsiderFor(sample, j, unloaded));
  Vector free = (branch_ended[j] - w1) * gap;  // x_f,prior − x_c,prior
  free -= last_gain * h.dot(free);
  free += s.mean;
  const double p_tau = P(kTorque, kTorque);
  if (p_tau > 0.0) {
    const Vector column = P.col(kTorque);
    free -= (free[kTorque] / p_tau) * column;
    P.noalias() -= ((1.0 - p) / p_tau) * (column * column.transpose());
  }
  // What the instrument is (s, e) the branches share: a contact the chain
  // guesses at says nothing of it. The effort's offset β they do not: where
  // the load is 0 the effort's residual is β's.
  gap = s.mean - free;
  gap[kScale] = gap[kClearance] = 0.0;
  s.mean -= (1.0 - p) * gap;
  branch_spread[j] = std::sqrt(p * (1.0 - p)) * gap;
  branched[j] = true;
  P.noalias() += spread * spread.transpose();
}

// The branches' means through the prediction: F (b's row, tau's), and a
// held contact's tip stays while its load follows the bend where the free
// tip follows the encoder. (Each branch's shaft stepped at its own load
// served the filter a little but not the smoother, whose F does not know it:
// docs/decisions/contact-branches.md.)
void ComplianceFilter::Impl::PredictBranchGap(int j, double encoder_increment, double load_step) {
  if (!branched[j]) return;
  const FilterTransition& t = transition[j];
  for (Vector* v : {&branch_gap[j], &branch_spread[j]}) {  // D and E both by F, as P is F·P·Fᵀ
    Vector& x = *v;
    x[kBacklash] = t.f_backlash_torque * x[kTorque] + t.f_backlash_backlash * x[kBacklash] +
                   t.f_backlash_clearance * x[kClearance];
    x[kTorque] = t.f_torque_torque * x[kTorque] + t.f_torque_scale * x[kScale];
    x[kOffset] *= t.f_offset_offset;
  }
  // (Branches are kept only while the contact is inferred.)
  Vector& gap = branch_gap[j];
  gap[kTip] -= held_given_contact * encoder_increment;
  gap[kTorque] += held_given_contact * load_step;
}

// A quasi-static log without the hint: the chance that this pose goes on
// holding the last pose's contact (the chain's held move between two poses,
// QuasiStaticTransitions: the tip stays, the load follows the encoder). A
// pose at another depth, or an encoder jump, cannot hold it.
double ComplianceFilter::Impl::HeldPoseShare(const FilterSample& sample, int j,
                                             double previous_depth, bool jump) const {
  if (!options.quasi_static || !InfersContact(sample) || jump ||
      !(std::abs(depth - previous_depth) <= kMaxHeldDepthChange)) {
    return 0.0;
  }
  return branch_last[j];
}

// The pose's prediction as two branches (branch_gap): a contact that goes on
// holds the tip where it was and moves its load with the bend (the hint's
// held pose); a free tip starts again at the encoder (Reinitialise). The
// state's mean is their mixture at the share `held`, and the pose's effort
// then weighs the two (UpdateEffortBranches). Without it every pose
// started the tip anew, and a clamp's crossing of its clearance, where the
// load is nil, left the shaft's place to the prior.
void ComplianceFilter::Impl::PredictPoseBranches(int j, const FilterSample& sample, double dt,
                                                 double encoder_increment,
                                                 double extra_compliance, double held) {
  const FilterJointState before = joint[j];
  Predict(j, dt, true, false, encoder_increment, extra_compliance, 1.0);
  Reinitialise(j, sample, true);
  const FilterJointState contact = joint[j];
  joint[j] = before;
  // A free tip bears no load (the effort's update conditions this branch on
  // tau = 0): its shaft moves unloaded and its restart bends by none. From
  // the last pose's load it kept that pose's bend (a released hold's 0.5 N·m,
  // 30 mrad at the tip) and its wall.
  joint[j].mean[kTorque] = 0.0;
  Predict(j, dt, false, false, encoder_increment, extra_compliance, 0.0);
  Reinitialise(j, sample, false);
  FilterJointState& s = joint[j];
  const Vector d = contact.mean - s.mean;
  s.mean += held * d;
  // One covariance for both, the likelier branch's: a held tip's is a narrow
  // peak, a restarted one's the prior's breadth, and their moment-matched
  // Gaussian let each pose's encoder drag a held tip across the clearance
  // (docs/decisions/contact-branches.md).
  // The free tip's is kept for the effort's update (UpdateEffortBranches).
  has_pose_other[j] = held >= 0.5;
  if (held >= 0.5) {
    pose_other[j] = s.covariance;
    s.covariance = contact.covariance;
  }
  branch_gap[j] = d;
  // A free tip restarts at the encoder whether or not the last pose held a
  // contact: the mixing's free prior (x + (u − p)·D, UpdateEffortBranches)
  // takes nothing of the held tip. With u the chain's share of an ended
  // contact, a hold the hint had made certain (p = 1, so u = 1) left the
  // next free pose's tip where the hold was, 0.2 rad from its encoder
  // (experiments/third_generator).
  branch_ended[j] = 0.0;
  branch_spread[j] = std::sqrt(held * (1.0 - held)) * d;
  branched[j] = true;
  s.covariance.noalias() += branch_spread[j] * branch_spread[j].transpose();
  // No one F maps the last pose to this mixture: the smoother does not link them.
  transition[j].predicted = false;
}

}  // namespace pliant::estimation
