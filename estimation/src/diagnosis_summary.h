#pragma once
// The residual's summary in a diagnosis (its bias, RMS, whiteness and
// normality per joint) and the filter's NIS over the compared rows.
#include <vector>

#include "diagnosis_internal.h"
#include "pliant/estimation/diagnosis.h"
#include "pliant/io/log.h"

namespace pliant::estimation::diagnosis {

/// Residual entries of the used joints over the sensors' noise, joint 1's
/// run then joint 2's; `run` tells the segments (and joints) apart.
struct Standardised {
  std::vector<double> value;
  std::vector<int> run;
};
Standardised Standardise(const Problem& problem, const std::vector<Eigen::Vector2d>& residual);
double SumOfSquares(const std::vector<double>& x);

/// Bias and RMS per joint, the tip RMS, Ljung–Box and Jarque–Bera of a residual.
ResidualStatistics Summarise(const Problem& problem, const std::vector<Eigen::Vector2d>& residual,
                             const DiagnoseOptions& options);

/// The filter's mean NIS over the compared rows, with its χ² band (the
/// filter runs over every row of the log, in order).
void AddFilterNis(const io::Log& log, const models::ModelParameters& parameters,
                  const DiagnoseOptions& options, const Problem& problem, ResidualStatistics& s);

}  // namespace pliant::estimation::diagnosis
