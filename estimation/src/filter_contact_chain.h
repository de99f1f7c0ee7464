// The contact chain of the online filter without the tip_fixed hint
// (filter_contact.cpp): its prediction over a step, and its two rates,
// learned from the log's own contacts (docs/decisions/contact-rates.md).
#pragma once

#include "pliant/estimation/filter_options.h"

namespace pliant::estimation::filter_internal {

// The chain's rates, 1/s of chain time. FilterOptions' λ_on and λ_off are a
// Gamma prior worth one episode of each kind; the episodes the chain has
// believed and the chain time it spent free and in contact, forgotten over
// FilterOptions::contact_rate_memory_s, update it: a log of pushes teaches
// that contacts come often, a free log that they are rare.
class ContactRates {
 public:
  void Start(const FilterOptions& o);
  // One step of chain time chain_dt_s ending with this contact probability.
  void Learn(const FilterOptions& o, double probability, double chain_dt_s);
  double start_hz() const { return start_hz_; }
  double end_hz() const { return end_hz_; }

 private:
  double start_hz_ = 0.0, end_hz_ = 0.0;
  double onsets_ = 0.0, ends_ = 0.0;       // episodes believed, forgotten
  double free_s_ = 0.0, contact_s_ = 0.0;  // chain time at risk, forgotten
  bool believed_ = false;                  // inside an episode the chain believed
};

// What a free arm's own torque changes between two pair windows beyond the
// model's doubt of it (the learned torque's, the means' noise): a real arm's
// unmodelled friction and inertia, which pairs would otherwise read as a load
// following the encoder. Taught only by pairs that no held tip explains —
// the encoder crossed more than the clearance and the held law lost to the
// free one — weighted by the chain's odds that nothing held the tip: a push
// believed late cannot teach it (docs/decisions/contact-pair-windows.md).
class FreeArmPairChange {
 public:
  double variance_nm2() const { return variance_; }
  // A closed pair: its effort change, the model's variance of it, and the
  // share of it that only the free law explains (0: it could be a held tip's).
  void Offer(double change_nm, double model_nm2, double free_share);
  // The row that closed it, once the chain has weighed it: taught with `free_weight`.
  void Learn(double free_weight);

 private:
  double variance_ = 0.0, lessons_ = 0.0;  // a running mean over the last 50 pairs
  double change_nm_ = 0.0, model_nm2_ = 0.0, share_ = 0.0;
};

// The contact chain's prediction for one step (filter_contact.cpp).
struct ContactPrior {
  double probability = 0.0;  // of contact, before this step's effort
  double continuing = 0.0;   // the share of it that is the last step's contact going on
  double ended = 0.0;        // the share of no contact that is the last step's contact ending
};
ContactPrior MixContact(const FilterOptions& o, const ContactRates& rates, double probability,
                        double dt);

// log N(x; 0, v): the chain's Gaussian densities (a settled free arm's
// residual, the pose pairs' laws).
double LogNormal(double x, double v);
// log density of a contact's residual |r|² over `joints` (1 or 2) joints:
// a load of uniform direction and log-uniform scale s, s² in [s_lo2, s_hi2]
// (filter_contact_evidence.cpp).
double ContactLogDensity(double radius2_nm2, int joints, double s_lo2, double s_hi2);

}  // namespace pliant::estimation::filter_internal
