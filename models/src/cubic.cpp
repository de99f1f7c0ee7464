#include "pliant/models/cubic.h"

#include <algorithm>
#include <cmath>

namespace pliant::models {

double Cubic::MinimumOn(double lower, double upper) const {
  const Cubic& p = *this;
  double minimum = std::min(p(lower), p(upper));
  const double a = 3.0 * coefficients[0];
  const double b = 2.0 * coefficients[1];
  const double c = coefficients[2];
  auto consider = [&](double x) {
    if (x > lower && x < upper) minimum = std::min(minimum, p(x));
  };
  if (a == 0.0) {
    if (b != 0.0) consider(-c / b);
    return minimum;
  }
  const double discriminant = b * b - 4.0 * a * c;
  if (discriminant < 0.0) return minimum;
  // The numerically stable pair of roots (no cancellation between b and sqrt).
  const double q = -0.5 * (b + std::copysign(std::sqrt(discriminant), b));
  if (q != 0.0) consider(c / q);
  consider(q / a);
  return minimum;
}

}  // namespace pliant::models
