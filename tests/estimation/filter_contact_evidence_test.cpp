// The contact's evidence in closed form (filter_contact_evidence.cpp) against
// the scale mixture it integrates, by quadrature; what a free arm's pairs
// teach of its own torque's change.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "../../estimation/src/filter_contact_chain.h"

namespace pliant::estimation::filter_internal {
namespace {

constexpr double kPi = 3.14159265358979323846;

// log of ∫ Π_j N(r_j; 0, s²) d(log s) / ln(s_hi/s_lo) over s in [s_lo, s_hi],
// by the midpoint rule on 20,000 steps of log s.
double Quadrature(double radius2, int joints, double s_lo2, double s_hi2) {
  const int n = 20000;
  const double a = 0.5 * std::log(s_lo2), b = 0.5 * std::log(s_hi2);
  double sum = 0.0;
  for (int k = 0; k < n; ++k) {
    const double s2 = std::exp(2.0 * (a + (k + 0.5) * (b - a) / n));
    sum += std::exp(-0.5 * radius2 / s2) / std::pow(2.0 * kPi * s2, 0.5 * joints);
  }
  return std::log(sum / n);
}

TEST(ContactLogDensity, IsTheScaleMixtureInClosedForm) {
  for (int joints : {1, 2}) {
    for (double radius : {0.0, 1e-5, 0.01, 0.1, 0.31, 1.0, 3.0, 10.0}) {
      const double s_lo2 = 0.05 * 0.05 + 0.01, s_hi2 = 3.3 * 3.3 + 0.01;
      EXPECT_NEAR(ContactLogDensity(radius * radius, joints, s_lo2, s_hi2),
                  Quadrature(radius * radius, joints, s_lo2, s_hi2), 1e-6)
          << joints << " joints, |r| " << radius;
    }
  }
}

// A free arm at rest, σ 0.09 N·m per joint, and a 0.31 N·m load along
// joint 1: the contact is favoured (the slab N(0, 1) per joint gave 1.06
// nats, the still joint's zero charged 2.4 of them), and a zero residual
// still favours no contact.
TEST(ContactLogDensity, ALoadAlongOneJointIsEvidenceAndNoneIsNot) {
  const double s_lo2 = 0.0025;
  const double v = 0.09 * 0.09;
  const double free = LogNormal(0.31, v) + LogNormal(0.0, v);
  const double contact = ContactLogDensity(0.31 * 0.31, 2, s_lo2 + v, 3.3 * 3.3 + v);
  EXPECT_NEAR(contact - free, 2.2, 0.1);
  EXPECT_LT(ContactLogDensity(0.0, 2, s_lo2 + v, 3.3 * 3.3 + v) - 2.0 * LogNormal(0.0, v), -1.0);
}

// Pairs whose change is N(0, σ_m² + σ_x²) and whose model says σ_m²: the
// running mean learns the excess σ_x² (0.05² N·m² here, 0.0065² the model's,
// the real bag's free arm: docs/decisions/contact-pair-windows.md) to within
// its sampling error over the last 50 pairs (a χ² of 50: ±20 % at 1σ, ±60 %
// stated), and only from pairs that the free law alone explains and the
// chain calls free.
TEST(FreeArmPairChange, LearnsTheChangeBeyondTheModelFromFreePairsOnly) {
  std::mt19937 rng(5);
  const double model = 0.0065 * 0.0065, excess = 0.05 * 0.05;
  std::normal_distribution<double> change(0.0, std::sqrt(model + excess));
  FreeArmPairChange learned, held_tip, chain_sure_of_contact;
  for (int k = 0; k < 400; ++k) {
    const double c = change(rng);
    learned.Offer(c, model, 1.0);
    learned.Learn(1.0);
    held_tip.Offer(c, model, 0.0);  // travel within the clearance: a held tip's crossing
    held_tip.Learn(1.0);
    chain_sure_of_contact.Offer(c, model, 1.0);
    chain_sure_of_contact.Learn(0.0);
  }
  EXPECT_NEAR(learned.variance_nm2(), excess, 0.6 * excess);
  EXPECT_EQ(held_tip.variance_nm2(), 0.0);
  EXPECT_EQ(chain_sure_of_contact.variance_nm2(), 0.0);
  // A pair is taught once: a second Learn without an Offer teaches nothing.
  FreeArmPairChange once;
  once.Offer(0.1, model, 1.0);
  once.Learn(1.0);
  const double after_one = once.variance_nm2();
  once.Learn(1.0);
  EXPECT_EQ(once.variance_nm2(), after_one);
  // Winsorised at 3σ of the free law: the first lesson of a 1 N·m change is
  // 9·σ_m² − σ_m² = 8·σ_m², not 1 N·m².
  EXPECT_NEAR(after_one, 8.0 * model, 1e-12);
}

}  // namespace
}  // namespace pliant::estimation::filter_internal
