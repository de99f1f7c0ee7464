#pragma once
// Cubic polynomials in the insertion depth L (m): the paper's 1/K(L) fits
// (equations 3 and 4) and the dVRK parameter file's direct K(L) fit.

#include <array>

namespace pliant::models {

/// c[0]·x³ + c[1]·x² + c[2]·x + c[3] by Horner's rule, for any scalar type.
template <typename T, typename C>
T Horner3(const C* c, const T& x) {
  return ((T(c[0]) * x + T(c[1])) * x + T(c[2])) * x + T(c[3]);
}

/// p(L) = c3·L³ + c2·L² + c1·L + c0, coefficients highest power first, as the
/// paper prints them.
struct Cubic {
  std::array<double, 4> coefficients{};  // {c3, c2, c1, c0}

  template <typename T>
  T operator()(const T& x) const {
    return Horner3(coefficients.data(), x);
  }

  /// Smallest value of p on [lower, upper]. Exact: a cubic's minimum on an
  /// interval lies at an end or at a root of p'(x) = 3·c3·x² + 2·c2·x + c1.
  double MinimumOn(double lower, double upper) const;
};

}  // namespace pliant::models
