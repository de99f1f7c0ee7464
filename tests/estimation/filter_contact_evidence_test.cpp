// The contact's evidence in closed form (filter_contact_evidence.cpp) against
// the scale mixture it integrates, by quadrature.
#include <cmath>

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

}  // namespace
}  // namespace pliant::estimation::filter_internal
