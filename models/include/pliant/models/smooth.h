#pragma once
// Smooth shapes shared by effects that must stay differentiable for the filter
// and the smoother.

namespace pliant::models {

/// S(x) = (15x − 10x³ + 3x⁵)/8 on |x| < 1, ±1 beyond: odd, S'(0) = 15/8, and
/// S, S', S'' continuous at |x| = 1, so it reaches ±1 exactly and smoothly. It is
/// the integral of (1 − x²)², scaled to end at 1.
template <typename T>
T SmoothSaturation(const T& x) {
  if (x >= 1.0) return T(1.0);
  if (x <= -1.0) return T(-1.0);
  const T x2 = x * x;
  return x * (T(15.0) - x2 * (T(10.0) - T(3.0) * x2)) / T(8.0);
}

}  // namespace pliant::models
