#pragma once
// χ² quantiles (Boost.Math) for the filter's gates and its mismatch test.
// Computed once, at construction: never inside Step().

namespace pliant::estimation::internal {

/// The p-quantile of χ² with `dof` degrees of freedom (dof > 0, 0 < p < 1).
double ChiSquaredQuantile(double dof, double p);

}  // namespace pliant::estimation::internal
