// The arm's dynamics fitted on free motion (pliant/estimation/free_motion_fit.h).
#include "pliant/estimation/free_motion_fit.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <set>

#include <ceres/ceres.h>

#include "clustered_sandwich.h"
#include "diagnosis_internal.h"
#include "pliant/estimation/effect_inputs.h"
#include "pliant/estimation/extra_effects.h"
#include "pliant/io/input_error.h"

namespace pliant::estimation {
namespace {

constexpr double kMovingRadS = 0.05;  // FreeMotionSeconds' "moves"
constexpr double kMinFreeMotionS = 1.0;

struct FreeRow {
  models::JointState<double> state;
  Eigen::Vector2d target_nm{0.0, 0.0};  // τ − τ₀ − the file's other internal effects
  bool used[2] = {false, false};
  int log = 0;
  double time_s = 0.0;
};

bool TipHeld(const io::Log& log, const io::StandardColumns& c, std::size_t r) {
  return c.tip_fixed >= 0 && log.Value(r, c.tip_fixed) > 0.5;
}

// The free rows of one log, each with what the effects see (the effort's rate
// and the acceleration centred, as the diagnosis reads them).
void CollectRows(const io::Log& log, int index, const models::ModelParameters& parameters,
                 const ExtraEffects& others, std::vector<FreeRow>* rows) {
  const io::StandardColumns c(log.header);
  EffectInputs inputs(false);
  const auto rate = CentredEffortRates(log);
  const auto acceleration = CentredAccelerations(log);
  const int tau[2] = {c.tau1, c.tau2};
  for (std::size_t r = 0; r < log.Rows(); ++r) {
    FreeRow row;
    row.state = inputs.Update(c, &log.values[r * log.Columns()]);
    if (TipHeld(log, c, r)) continue;
    row.state.effort_rate_nm_s = rate[r];
    row.state.acceleration_rad_s2 = acceleration[r];
    const auto& s = row.state;
    if (!s.encoder_angle_rad.allFinite() || !std::isfinite(s.insertion_depth_m)) continue;
    const Eigen::Vector2d other = others.InternalTorque(s);
    for (int j = 0; j < 2; ++j) {
      const double effort = tau[j] >= 0 ? log.Value(r, tau[j]) : NAN;
      row.target_nm[j] = effort - other[j] -
                         models::BiasTorqueAt(parameters.joints[j], s.encoder_angle_rad[j],
                                              s.insertion_depth_m);
      row.used[j] = log.header.JointRecorded(j + 1) && std::isfinite(row.target_nm[j]);
      if (!row.used[j]) row.target_nm[j] = 0.0;
    }
    if (!row.used[0] && !row.used[1]) continue;
    row.log = index;
    row.time_s = s.time_s;
    rows->push_back(row);
  }
}

// One block of rows: residual (target − Σ effects)/σ_j per row and joint,
// one parameter block per effect. The effects' derivatives are their own
// code's, by Jet (EffectJet, eight parameters a pass).
class BlockCost final : public ceres::CostFunction {
 public:
  BlockCost(const std::vector<FreeRow>& rows, std::size_t first, std::size_t last,
            const std::vector<std::unique_ptr<EffectModel>>& effects, Eigen::Vector2d sd)
      : rows_(rows), first_(first), last_(last), effects_(effects), sd_(sd) {
    set_num_residuals(int(2 * (last - first)));
    for (const auto& e : effects) mutable_parameter_block_sizes()->push_back(int(e->Parameters().size()));
  }

  bool Evaluate(double const* const* p, double* residuals, double** jacobians) const override {
    const std::size_t m = effects_.size();
    for (std::size_t i = first_; i < last_; ++i) {
      const FreeRow& row = rows_[i];
      Eigen::Vector2d sum = Eigen::Vector2d::Zero();
      for (std::size_t e = 0; e < m; ++e) sum += effects_[e]->Evaluate(p[e], row.state);
      for (int j = 0; j < 2; ++j) {
        residuals[2 * (i - first_) + j] =
            row.used[j] ? (row.target_nm[j] - sum[j]) / sd_[j] : 0.0;
      }
    }
    if (!jacobians) return true;
    for (std::size_t e = 0; e < m; ++e) {
      if (jacobians[e]) EffectJacobian(e, p[e], jacobians[e]);
    }
    return true;
  }

 private:
  void EffectJacobian(std::size_t e, const double* values, double* jacobian) const {
    const int n = int(effects_[e]->Parameters().size());
    Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> d(
        jacobian, num_residuals(), n);
    std::vector<EffectJet> jets(std::size_t(n), EffectJet(0.0));
    for (int start = 0; start < n; start += kEffectJetSize) {
      for (int k = 0; k < n; ++k) {
        jets[std::size_t(k)] = EffectJet(values[k]);
        if (k >= start && k < start + kEffectJetSize) jets[std::size_t(k)].v[k - start] = 1.0;
      }
      for (std::size_t i = first_; i < last_; ++i) {
        const auto out = effects_[e]->Evaluate(jets.data(), rows_[i].state.Cast<EffectJet>());
        for (int j = 0; j < 2; ++j) {
          const Eigen::Index row = Eigen::Index(2 * (i - first_) + j);
          for (int k = start; k < std::min(n, start + kEffectJetSize); ++k)
            d(row, k) = rows_[i].used[j] ? -out[j].v[k - start] / sd_[j] : 0.0;
        }
      }
    }
  }

  const std::vector<FreeRow>& rows_;
  std::size_t first_, last_;
  const std::vector<std::unique_ptr<EffectModel>>& effects_;
  Eigen::Vector2d sd_;
};

// Consecutive rows of one log, each at most block_s long.
std::vector<std::pair<std::size_t, std::size_t>> Blocks(const std::vector<FreeRow>& rows,
                                                        double block_s) {
  std::vector<std::pair<std::size_t, std::size_t>> blocks;
  std::size_t first = 0;
  for (std::size_t i = 1; i <= rows.size(); ++i) {
    if (i == rows.size() || rows[i].log != rows[first].log ||
        rows[i].time_s - rows[first].time_s >= block_s) {
      blocks.emplace_back(first, i);
      first = i;
    }
  }
  return blocks;
}

struct Fit {
  std::vector<std::vector<double>> values;
  Eigen::VectorXd residual_nm;  // per row and joint (0 where unused)
  Eigen::MatrixXd covariance;   // over the effects' parameters (empty unless asked)
  int clusters = 0;
};

// covariance_floor: how many rows a correlation time spans (2τ/dt, the
// variance factor of a mean over AR(1) errors): the white-noise covariance
// times it is the least the σ may be where the blocks are too few to show it.
Fit Solve(const std::vector<FreeRow>& rows, const std::vector<std::unique_ptr<EffectModel>>& effects,
          Fit start, const Eigen::Vector2d& sd, double block_s, double covariance_floor) {
  ceres::Problem::Options options;
  options.cost_function_ownership = ceres::TAKE_OWNERSHIP;
  ceres::Problem problem(options);
  std::vector<double*> blocks;
  for (auto& values : start.values) blocks.push_back(values.data());
  std::vector<ceres::ResidualBlockId> ids;
  std::vector<int> cluster_of_row;
  const auto chunks = Blocks(rows, block_s);
  for (std::size_t b = 0; b < chunks.size(); ++b) {
    const auto [first, last] = chunks[b];
    ids.push_back(problem.AddResidualBlock(new BlockCost(rows, first, last, effects, sd), nullptr,
                                           blocks));
    cluster_of_row.insert(cluster_of_row.end(), 2 * (last - first), int(b));
  }
  for (std::size_t e = 0; e < effects.size(); ++e) {
    ids.push_back(diagnosis::AddEffectPrior(&problem, blocks[e], *effects[e]));
    cluster_of_row.insert(cluster_of_row.end(), effects[e]->Parameters().size(), -1);
  }
  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::DENSE_QR;
  solver.max_num_iterations = 200;
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);
  Fit out = std::move(start);
  Eigen::SparseMatrix<double> jacobian;
  Eigen::VectorXd r;
  detail::EvaluateJacobian(&problem, blocks, ids, &jacobian, &r);
  out.residual_nm = r.head(Eigen::Index(2 * rows.size()));
  for (std::size_t i = 0; i < rows.size(); ++i)
    for (int j = 0; j < 2; ++j) out.residual_nm[Eigen::Index(2 * i + j)] *= sd[j];
  out.clusters = int(chunks.size());
  if (!(covariance_floor > 0.0)) return out;
  std::vector<Eigen::Index> wanted;  // the named effects' (the table's correction is last)
  Eigen::Index column = 0;
  for (std::size_t e = 0; e + 1 < effects.size(); ++e)
    for (std::size_t k = 0; k < effects[e]->Parameters().size(); ++k) wanted.push_back(column++);
  // Longer blocks too, while ten remain: the residual's correlation time
  // misses a slow misfit that white noise hides (detail::BlockedSandwich).
  const auto sandwich = detail::BlockedSandwich(jacobian, r, cluster_of_row, wanted, 10);
  const Eigen::MatrixXd floor = covariance_floor * sandwich.model;
  out.covariance = out.clusters >= 2 ? detail::NotBelow(sandwich.clustered, floor) : floor;
  return out;
}

// The residual's autocorrelation at `lag` rows (consecutive rows of one log).
double Autocorrelation(const std::vector<FreeRow>& rows, const Eigen::VectorXd& residual, int j,
                       std::size_t lag, double variance) {
  double sum = 0.0;
  for (std::size_t i = lag; i < rows.size(); ++i) {
    if (rows[i].log == rows[i - lag].log && rows[i].used[j] && rows[i - lag].used[j])
      sum += residual[Eigen::Index(2 * i + j)] * residual[Eigen::Index(2 * (i - lag) + j)];
  }
  return sum / variance;
}

// The residual's correlation time, s: the first lag whose autocorrelation
// (over consecutive rows of one log, both joints) falls below 1/e — found by
// doubling the lag, then halving the bracket (the autocorrelation taken as
// falling): O(n log lag), where every lag in turn would cost O(n·lag) on a
// long log at 1.5 kHz.
double CorrelationSeconds(const std::vector<FreeRow>& rows, const Eigen::VectorXd& residual) {
  double worst = 0.0;
  for (int j = 0; j < 2; ++j) {
    double variance = 0.0, dt_sum = 0.0;
    std::size_t n = 0;
    for (std::size_t i = 0; i < rows.size(); ++i) {
      if (!rows[i].used[j]) continue;
      variance += std::pow(residual[Eigen::Index(2 * i + j)], 2);
      if (i > 0 && rows[i - 1].log == rows[i].log) dt_sum += rows[i].time_s - rows[i - 1].time_s;
      ++n;
    }
    if (n < 20 || !(variance > 0.0)) continue;
    const auto below = [&](std::size_t lag) {
      return Autocorrelation(rows, residual, j, lag, variance) < std::exp(-1.0);
    };
    std::size_t high = 1;
    while (high < n / 10 && !below(high)) high *= 2;
    if (high >= n / 10) continue;  // never decorrelates within a tenth of the log
    std::size_t low = high / 2;    // above 1/e there (or 0)
    while (high - low > 1) {
      const std::size_t mid = (low + high) / 2;
      (below(mid) ? high : low) = mid;
    }
    worst = std::max(worst, double(high) * dt_sum / double(n - 1));
  }
  return worst;
}

// The median step between consecutive rows of one log, s.
double RowSeconds(const std::vector<FreeRow>& rows) {
  std::vector<double> steps;
  for (std::size_t i = 1; i < rows.size(); ++i)
    if (rows[i].log == rows[i - 1].log) steps.push_back(rows[i].time_s - rows[i - 1].time_s);
  if (steps.empty()) return 1.0;
  std::nth_element(steps.begin(), steps.begin() + long(steps.size() / 2), steps.end());
  return steps[steps.size() / 2];
}

Eigen::Vector2d Rms(const std::vector<FreeRow>& rows, const Eigen::VectorXd& residual) {
  Eigen::Vector2d sum(0.0, 0.0), n(0.0, 0.0);
  for (std::size_t i = 0; i < rows.size(); ++i)
    for (int j = 0; j < 2; ++j)
      if (rows[i].used[j]) sum[j] += std::pow(residual[Eigen::Index(2 * i + j)], 2), n[j] += 1.0;
  return (sum.array() / n.array().max(1.0)).sqrt();
}

std::vector<EffectFinding> Findings(const std::vector<std::unique_ptr<EffectModel>>& effects,
                                    const Fit& fit) {
  std::vector<EffectFinding> out;
  Eigen::Index column = 0;
  for (std::size_t e = 0; e + 1 < effects.size(); ++e) {
    EffectFinding f;
    f.name = std::string(effects[e]->Info().name);
    f.description = std::string(effects[e]->Info().explanation);
    f.channels = diagnosis::ChannelsOf(*effects[e]);
    f.parameters = fit.values[e];
    for (const auto& spec : effects[e]->Parameters()) {
      f.parameter_names.push_back(spec.name);
      f.parameter_sd.push_back(std::sqrt(std::max(0.0, fit.covariance(column, column))));
      ++column;
    }
    f.size_unit = "N·m";
    out.push_back(std::move(f));
  }
  return out;
}

// An internal torque that reads only these channels (ChannelsOf).
bool ReadsOnly(const std::string& name, const std::set<std::string>& allowed) {
  if (!EffectCatalogue::Global().Contains(name)) return false;
  const auto effect = EffectCatalogue::Global().Create(name);
  if (effect->Info().channel != models::Channel::kInternalTorque) return false;
  const auto channels = diagnosis::ChannelsOf(*effect);
  return !channels.empty() && std::all_of(channels.begin(), channels.end(),
                                          [&](const std::string& c) { return allowed.count(c) > 0; });
}
}  // namespace

bool FittedFromFreeMotion(const std::string& name) {
  return ReadsOnly(name, {"v1", "v2", "d2q1/dt2", "d2q2/dt2"});
}

bool ReadsOnlyTheAcceleration(const std::string& name) {
  return ReadsOnly(name, {"d2q1/dt2", "d2q2/dt2"});
}

std::vector<std::string> FreeMotionEffectNames() {
  std::vector<std::string> names;
  for (const auto& name : EffectCatalogue::Global().Names())
    if (FittedFromFreeMotion(name)) names.push_back(name);
  return names;
}

double FreeMotionSeconds(const io::Log& log) {
  if (log.header.QuasiStatic()) return 0.0;
  const io::StandardColumns c(log.header);
  EffectInputs inputs(false);
  double seconds = 0.0, last = NAN;
  for (std::size_t r = 0; r < log.Rows(); ++r) {
    const auto& s = inputs.Update(c, &log.values[r * log.Columns()]);
    const double dt = s.time_s - last;
    last = s.time_s;
    if (TipHeld(log, c, r) || !(dt > 0.0 && dt <= 0.1)) continue;
    if (s.velocity_rad_s.cwiseAbs().maxCoeff() > kMovingRadS) seconds += dt;
  }
  return seconds;
}

FreeMotionFit FitEffectsOnFreeMotion(const std::vector<NamedLog>& logs,
                                     const models::ModelParameters& parameters,
                                     const std::vector<std::string>& names) {
  std::vector<models::EffectParameters> kept;
  for (const auto& e : parameters.effects)
    if (std::find(names.begin(), names.end(), e.name) == names.end()) kept.push_back(e);
  const ExtraEffects others(kept);
  FreeMotionFit out;
  std::vector<FreeRow> rows;
  std::string all_paths;
  for (const NamedLog& named : logs) {
    all_paths += (all_paths.empty() ? "" : ", ") + named.path;
    if (FreeMotionSeconds(*named.log) < kMinFreeMotionS) continue;
    CollectRows(*named.log, int(out.logs.size()), parameters, others, &rows);
    out.logs.push_back(named.path);
  }
  if (!out.logs.empty() && rows.size() < 100) {
    throw io::InputError(all_paths, 0, 0,
                         "the free motion has " + std::to_string(rows.size()) +
                             " rows with finite angles, depth and efforts, too few to fit the "
                             "arm's dynamics on",
                         "record the efforts (tau1, tau2) while the arm moves freely");
  }
  if (out.logs.empty()) {
    throw io::InputError(all_paths, 0, 0,
                         "no log holds a second of free motion (a joint faster than 0.05 rad/s "
                         "with nothing holding the tip), and the arm's dynamics are fitted there",
                         "add a log of the arm moving freely (e.g. a recorded bag: pliant import)");
  }
  // The named effects, then the bias table's error along the path in the
  // catalogue's own law (bias_torque_fourier, from 0 with its prior): fitted
  // beside them, not written; without it the table's error, slow along the
  // path, would be read as the dynamics or make every row's error shared.
  std::vector<std::unique_ptr<EffectModel>> effects;
  Fit fit;
  for (const auto& name : names) effects.push_back(EffectCatalogue::Global().Create(name));
  effects.push_back(EffectCatalogue::Global().Create("bias_torque_fourier"));
  for (const auto& e : effects) fit.values.push_back(e->DefaultParameters());
  Eigen::VectorXd before(Eigen::Index(2 * rows.size()));
  Eigen::Vector2d mean(0.0, 0.0), count(0.0, 0.0);
  for (const FreeRow& row : rows)
    for (int j = 0; j < 2; ++j)
      if (row.used[j]) mean[j] += row.target_nm[j], count[j] += 1.0;
  mean = mean.cwiseQuotient(count.cwiseMax(1.0));
  for (std::size_t i = 0; i < rows.size(); ++i)
    for (int j = 0; j < 2; ++j)
      before[Eigen::Index(2 * i + j)] = rows[i].used[j] ? rows[i].target_nm[j] - mean[j] : 0.0;
  out.rows = rows.size();
  out.rms_before_nm = Rms(rows, before);
  const Eigen::Vector2d sd0 = out.rms_before_nm.cwiseMax(1e-6);
  Fit first = Solve(rows, effects, fit, sd0, kMinFreeMotionS, 0.0);
  // The second pass weighs each joint by its own residual and clusters by
  // ten of the residual's correlation times (at least a second).
  out.correlation_s = CorrelationSeconds(rows, first.residual_nm);
  out.block_s = std::max(kMinFreeMotionS, 10.0 * out.correlation_s);
  const Eigen::Vector2d sd = Rms(rows, first.residual_nm).cwiseMax(1e-6);
  const double row_s = RowSeconds(rows);
  const double floor = std::max(1.0, 2.0 * out.correlation_s / std::max(row_s, 1e-6));
  Fit final_fit = Solve(rows, effects, first, sd, out.block_s, floor);
  out.blocks = final_fit.clusters;
  out.rms_after_nm = Rms(rows, final_fit.residual_nm);
  out.fitted.effects = Findings(effects, final_fit);
  out.fitted.covariance = final_fit.covariance;
  if (out.blocks < 5 * int(final_fit.covariance.rows())) {
    out.notes.push_back("the σ rest on " + std::to_string(out.blocks) + " blocks of " +
                        std::to_string(out.block_s).substr(0, 4) +
                        " s for " + std::to_string(final_fit.covariance.rows()) +
                        " parameters: a longer log of free motion would state them more surely");
  }
  return out;
}

}  // namespace pliant::estimation
