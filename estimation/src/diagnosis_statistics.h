#pragma once
// Tests on the diagnosis's residual series (diagnosis_statistics.cpp).
#include <array>
#include <vector>

namespace pliant::estimation::diagnosis {

/// Lag-1 autocorrelation of a series cut into runs (a new run where `run`
/// changes); the AR(1) effective-size factor (1 − ρ)/(1 + ρ), in [1/n, 1].
double EffectiveSizeFactor(const std::vector<double>& x, const std::vector<int>& run);
struct TestResult {
  double statistic = 0.0;
  double p_value = 1.0;
};
TestResult LjungBox(const std::vector<double>& x, int lags);
TestResult JarqueBera(const std::vector<double>& x);
/// Upper tail of F(d1, d2) at f.
double FUpperTail(double f, double d1, double d2);
/// One-sided test that a mean gain is positive: Student's t on the per-block gains, g − 1
/// degrees of freedom. Rows within a segment are correlated; the held-out segments
/// (blocks) are what the cross-validation holds out, so they are the sample.
TestResult BlockImprovementTest(const std::vector<double>& gain_per_block);
/// Holm's step-down adjustment, in place.
void HolmAdjust(std::vector<double>& p_values);
/// Two-sided 95 % band of a mean of χ²/dof over `dof` degrees of freedom.
std::array<double, 2> ChiSquaredMeanBand(double dof);

}  // namespace pliant::estimation::diagnosis
