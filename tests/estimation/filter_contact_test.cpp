// Contact as the exception (FilterOptions::infer_contact). In free motion the
// effort holds the arm's own inertia and friction, which the bias torque does
// not model: without the tip_fixed hint the filter must not read them as a
// load and correct the tip by them (do no harm); a real contact, a load well
// beyond that level, must still be recognised and corrected.
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "../support/paper_parameters.h"
#include "pliant/estimation/filter.h"

namespace pliant::estimation {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kRate = 100.0;  // the dVRK 2.x CRTK topics' rate

struct Row {
  FilterSample sample;
  Eigen::Vector2d truth;
};

// 30 s of free motion at up to ~1 rad/s on joint 1: the effort holds
// J·q̈ + Coulomb and viscous friction (about 0.1 N·m RMS, 0.25 N·m peaks,
// the level of the real dVRK bag's unmodelled residual), and from
// contact_from_s for 3 s a load of contact_nm on joint 1, which bends the shaft.
std::vector<Row> FreeMotionWithInternalTorque(double contact_nm, double contact_from_s,
                                              unsigned seed) {
  const auto p = models::testing::PaperParameters();
  const FilterOptions o;
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<Row> rows;
  const double depth = 0.15;
  for (int k = 0; k < int(30 * kRate); ++k) {
    const double t = k / kRate;
    Row r;
    r.sample.time_s = t;
    r.sample.insertion_depth_m = depth;
    const Eigen::Vector2d w(2 * kPi * 0.35, 2 * kPi * 0.22);
    const Eigen::Vector2d a(0.45, 0.3);
    r.truth << a[0] * std::sin(w[0] * t), a[1] * std::sin(w[1] * t + 0.5);
    const Eigen::Vector2d velocity(a[0] * w[0] * std::cos(w[0] * t),
                                   a[1] * w[1] * std::cos(w[1] * t + 0.5));
    const Eigen::Vector2d acceleration = -w.cwiseProduct(w).cwiseProduct(r.truth);
    const bool contact = t >= contact_from_s && t < contact_from_s + 3.0;
    for (int j = 0; j < 2; ++j) {
      const auto& jp = p.joints[j];
      const double load = (contact && j == 0) ? contact_nm : 0.0;
      const double internal = 0.04 * acceleration[j] + 0.08 * std::tanh(velocity[j] / 0.05) +
                              0.03 * velocity[j];
      const double bend = load != 0.0 ? jp.backlash_rad * std::copysign(1.0, load) +
                                            models::ComplianceAt(jp, depth) * load
                                      : 0.0;
      r.sample.encoder_rad[j] = r.truth[j] + bend + o.encoder_noise_rad * normal(rng);
      r.sample.effort_nm[j] = models::BiasTorqueAt(jp, r.sample.encoder_rad[j], depth) +
                              internal + load + o.effort_noise_nm * normal(rng);
    }
    rows.push_back(r);
  }
  return rows;
}

TEST(FilterContact, FreeMotionIsNotCorrectedByTheArmsOwnTorque) {
  const auto rows = FreeMotionWithInternalTorque(0.0, 1e9, 1);
  ComplianceFilter filter(models::testing::PaperParameters());
  std::vector<double> correction;
  int within_two_sd = 0;
  for (const Row& r : rows) {
    const FilterEstimate e = filter.Step(r.sample);
    correction.push_back(e.tip_correction_mm);
    within_two_sd += e.tip_correction_mm <= 2.0 * e.tip_correction_sd_mm;
  }
  std::nth_element(correction.begin(), correction.begin() + correction.size() / 2,
                   correction.end());
  // Issue 26 item 5's acceptance on the real bag: median ≤ 0.3 mm, ≥ 95 % within 2σ.
  EXPECT_LE(correction[correction.size() / 2], 0.3);
  EXPECT_GE(within_two_sd, 0.95 * double(rows.size()));
}

TEST(FilterContact, AContactBeyondTheArmsOwnTorqueIsStillCorrected) {
  const auto rows = FreeMotionWithInternalTorque(0.8, 12.0, 2);
  ComplianceFilter filter(models::testing::PaperParameters());
  double worst = 0.0, sure = 1.0;
  for (const Row& r : rows) {
    const FilterEstimate e = filter.Step(r.sample);
    // From 0.3 s into the 3 s contact to its end.
    if (r.sample.time_s >= 12.3 && r.sample.time_s < 15.0) {
      worst = std::max(worst, std::abs(e.corrected_rad[0] - r.truth[0]));
      sure = std::min(sure, e.contact_probability[0]);
    }
  }
  EXPECT_GT(sure, 0.99);
  // The deflection is 0.8 N·m · K + δ ≈ 59 mrad; left: the friction's share of
  // the load (≤ 0.1 N·m, 6 mrad) and the shaft's place.
  EXPECT_LT(worst, 0.008);
}

}  // namespace
}  // namespace pliant::estimation
