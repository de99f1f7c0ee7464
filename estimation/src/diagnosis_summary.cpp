// The residual's summary in a diagnosis and the filter's NIS over the
// compared rows (diagnosis_summary.h).
#include "diagnosis_summary.h"

#include <cmath>

#include "pliant/estimation/filter.h"
#include "pliant/estimation/filter_log.h"

namespace pliant::estimation::diagnosis {

Standardised Standardise(const Problem& problem, const std::vector<Eigen::Vector2d>& r) {
  Standardised out;
  for (int j = 0; j < 2; ++j) {
    for (std::size_t i = 0; i < r.size(); ++i) {
      if (!problem.samples[i].used[j]) continue;
      out.value.push_back(r[i][j] / problem.noise_sd_rad[j]);
      out.run.push_back(2 * problem.samples[i].group + j);
    }
  }
  return out;
}

double SumOfSquares(const std::vector<double>& x) {
  double s = 0.0;
  for (double v : x) s += v * v;
  return s;
}

ResidualStatistics Summarise(const Problem& problem, const std::vector<Eigen::Vector2d>& r,
                             const DiagnoseOptions& o) {
  ResidualStatistics s;
  s.samples = r.size();
  s.rms_mm = TipRmsMm(problem, r);
  for (int j = 0; j < 2; ++j) {
    double sum = 0.0, square = 0.0, n = 0.0;
    for (std::size_t i = 0; i < r.size(); ++i) {
      if (!problem.samples[i].used[j]) continue;
      sum += r[i][j], square += r[i][j] * r[i][j], n += 1.0;
    }
    s.bias_rad[j] = n > 0.0 ? sum / n : 0.0;
    s.rms_rad[j] = n > 0.0 ? std::sqrt(square / n) : 0.0;
  }
  const Standardised z = Standardise(problem, r);
  const auto lb = LjungBox(z.value, o.ljung_box_lags);
  const auto jb = JarqueBera(z.value);
  s.ljung_box_q = lb.statistic, s.ljung_box_p = lb.p_value;
  s.normality_statistic = jb.statistic, s.normality_p = jb.p_value;
  return s;
}

// The filter's NIS over the compared rows (it runs over every row in order).
void AddFilterNis(const io::Log& log, const models::ModelParameters& parameters,
                  const DiagnoseOptions& options, const Problem& problem, ResidualStatistics& s) {
  ComplianceFilter filter(parameters, options.filter);
  const io::StandardColumns columns(log.header);
  std::vector<bool> compared(log.Rows(), false);
  for (const auto& sample : problem.samples) compared[sample.row] = true;
  double nis = 0.0, dof = 0.0;
  for (std::size_t r = 0; r < log.Rows(); ++r) {
    const FilterEstimate e = filter.Step(
        SampleFromRow(columns, &log.values[r * log.Columns()], options.filter.fuse_log_reference));
    if (compared[r] && e.nis_dof > 0) nis += e.nis, dof += e.nis_dof;
  }
  s.mean_nis = dof > 0.0 ? nis / dof : 0.0;
  const auto band = ChiSquaredMeanBand(dof);
  s.nis_band[0] = band[0], s.nis_band[1] = band[1];
}

}  // namespace pliant::estimation::diagnosis
