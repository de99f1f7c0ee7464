// Ceres fit of effects as extensions of the model (docs/diagnose-method.md).
// The only diagnosis translation unit that differentiates: the effects are
// evaluated through the catalogue's EffectJet interface, 8 parameters at a
// time, inside one cost over all training samples. That one cost also
// profiles the tip angle out (tip_fixed: subtract each segment's mean from
// the residuals and from their Jacobian rows), which a per-sample cost could
// not do without one nuisance parameter block per segment.
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <ceres/ceres.h>

#include "clustered_sandwich.h"
#include "diagnosis_internal.h"

namespace pliant::estimation::diagnosis {
namespace {

class ResidualCost final : public ceres::CostFunction {
 public:
  ResidualCost(const Problem& problem, const BaseModel& model, std::vector<Term> terms,
               std::size_t first_fitted, std::vector<std::size_t> samples)
      : problem_(problem), model_(model), terms_(std::move(terms)), first_fitted_(first_fitted),
        samples_(std::move(samples)) {
    set_num_residuals(int(2 * samples_.size()));
    for (std::size_t t = first_fitted_; t < terms_.size(); ++t)
      mutable_parameter_block_sizes()->push_back(int(terms_[t].parameters.size()));
    for (std::size_t t = 0; t < terms_.size(); ++t) {
      jet_constants_.emplace_back();
      for (double v : terms_[t].parameters) jet_constants_.back().emplace_back(v);
    }
  }

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    const std::size_t n = samples_.size();
    std::vector<const double*> values;
    std::vector<std::vector<EffectJet>> jets = jet_constants_;
    for (std::size_t t = 0; t < terms_.size(); ++t) {
      const bool fitted = t >= first_fitted_;
      values.push_back(fitted ? parameters[t - first_fitted_] : terms_[t].parameters.data());
      if (fitted) {
        for (std::size_t k = 0; k < jets[t].size(); ++k) jets[t][k] = EffectJet(values[t][k]);
      }
    }
    for (std::size_t i = 0; i < n; ++i) {
      const Sample& s = problem_.samples[samples_[i]];
      const Eigen::Vector2d r = ModelResidual<double>(s, model_, terms_, values);
      for (int j = 0; j < 2; ++j)
        residuals[2 * i + j] = s.used[j] ? r[j] / problem_.noise_sd_rad[j] : 0.0;
    }
    Profile(residuals, 1);
    if (!jacobians) return true;
    for (std::size_t t = first_fitted_; t < terms_.size(); ++t) {
      double* jacobian = jacobians[t - first_fitted_];
      if (!jacobian) continue;
      const int size = int(terms_[t].parameters.size());
      for (int start = 0; start < size; start += kEffectJetSize) {
        std::vector<std::vector<EffectJet>> seeded = jets;
        for (int k = start; k < std::min(size, start + kEffectJetSize); ++k)
          seeded[t][k].v[k - start] = 1.0;
        std::vector<const EffectJet*> pointers;
        for (const auto& block : seeded) pointers.push_back(block.data());
        for (std::size_t i = 0; i < n; ++i) {
          const Sample& s = problem_.samples[samples_[i]];
          const models::Vec2<EffectJet> r = ModelResidual<EffectJet>(s, model_, terms_, pointers);
          for (int j = 0; j < 2; ++j) {
            for (int k = start; k < std::min(size, start + kEffectJetSize); ++k) {
              jacobian[(2 * i + j) * size + k] =
                  s.used[j] ? r[j].v[k - start] / problem_.noise_sd_rad[j] : 0.0;
            }
          }
        }
      }
      Profile(jacobian, size);
    }
    return true;
  }

 private:
  // Subtracts each group's mean (over its used entries) from rows of width
  // `width`: the tip angle of a held segment is unknown.
  void Profile(double* rows, int width) const {
    if (!problem_.profile_tip) return;
    const int g = problem_.tip_groups;
    std::vector<double> sum(std::size_t(2 * g * width), 0.0), count(std::size_t(2 * g), 0.0);
    for (std::size_t i = 0; i < samples_.size(); ++i) {
      const Sample& s = problem_.samples[samples_[i]];
      for (int j = 0; j < 2; ++j) {
        if (!s.used[j]) continue;
        count[2 * s.tip_group + j] += 1.0;
        for (int k = 0; k < width; ++k) sum[(2 * s.tip_group + j) * width + k] += rows[(2 * i + j) * width + k];
      }
    }
    for (std::size_t i = 0; i < samples_.size(); ++i) {
      const Sample& s = problem_.samples[samples_[i]];
      for (int j = 0; j < 2; ++j) {
        if (!s.used[j]) continue;
        const double c = count[2 * s.tip_group + j];
        for (int k = 0; k < width; ++k)
          rows[(2 * i + j) * width + k] -= sum[(2 * s.tip_group + j) * width + k] / c;
      }
    }
  }

  const Problem& problem_;
  const BaseModel& model_;
  std::vector<Term> terms_;
  std::size_t first_fitted_;
  std::vector<std::size_t> samples_;
  std::vector<std::vector<EffectJet>> jet_constants_;
};

// Gaussian prior (p − default)/sd on each parameter of a block.
class PriorCost final : public ceres::CostFunction {
 public:
  explicit PriorCost(std::vector<models::ParameterSpec> specs) : specs_(std::move(specs)) {
    set_num_residuals(int(specs_.size()));
    mutable_parameter_block_sizes()->push_back(int(specs_.size()));
  }
  bool Evaluate(double const* const* p, double* residuals, double** jacobians) const override {
    const int n = int(specs_.size());
    for (int k = 0; k < n; ++k) residuals[k] = (p[0][k] - specs_[k].default_value) / specs_[k].prior_sd;
    if (jacobians && jacobians[0]) {
      std::fill(jacobians[0], jacobians[0] + n * n, 0.0);
      for (int k = 0; k < n; ++k) jacobians[0][k * n + k] = 1.0 / specs_[k].prior_sd;
    }
    return true;
  }

 private:
  std::vector<models::ParameterSpec> specs_;
};

}  // namespace

ceres::ResidualBlockId AddEffectPrior(ceres::Problem* problem, double* block,
                                      const EffectModel& effect) {
  const auto specs = effect.Parameters();
  const ceres::ResidualBlockId id = problem->AddResidualBlock(new PriorCost(specs), nullptr, block);
  for (std::size_t k = 0; k < specs.size(); ++k) {
    problem->SetParameterLowerBound(block, int(k), specs[k].lower_bound);
    problem->SetParameterUpperBound(block, int(k), specs[k].upper_bound);
  }
  return id;
}

namespace {

double ValueOf(double x) { return x; }
double ValueOf(const EffectJet& x) { return x.a; }

// The base model's own compliance and clearance, let loose: its K_j(L) scaled
// by 1 + s_j and d_j more clearance on the loaded wall. An identification
// whose log held the effect has bent K and δ to absorb it; refitted with each
// candidate they stop hiding it (and a candidate no longer wins by correcting
// K or δ alone). With `tilt` (an added effect's fit), K_j(L) is also tilted
// in depth by u_j (CompliancePerTilt): a clearance that grows with depth was
// identified as a K(L) that grows with depth, which one scale cannot undo.
// Candidates are scored without it: on a log with one load level the tilt
// mimics that clearance and would take its share from the candidate.
class BaseRecalibration {
 public:
  static constexpr models::EffectInfo kInfo{
      "base_recalibration", models::Channel::kDeflection,
      "the model's compliance scaled by 1 + s_j and tilted in depth by u_j, and its clearance "
      "widened by d_j, refitted with every candidate"};
  BaseRecalibration(const BaseModel& model, Recalibration kind) : model_(&model), kind_(kind) {
    for (int j = 0; j < 2; ++j) per_tilt_[j] = CompliancePerTilt(model.parameters().joints[j]);
  }
  std::vector<models::ParameterSpec> Parameters() const {
    std::vector<models::ParameterSpec> specs = {{"compliance_share1", "", 0.0, -0.5, 0.5, 0.2},
                                                {"compliance_share2", "", 0.0, -0.5, 0.5, 0.2},
                                                {"clearance1", "rad", 0.0, -0.005, 0.005, 0.002},
                                                {"clearance2", "rad", 0.0, -0.005, 0.005, 0.002}};
    if (kind_ != Recalibration::kScale) {
      specs.push_back({"compliance_tilt1", "", 0.0, -0.5, 0.5, 0.2});
      specs.push_back({"compliance_tilt2", "", 0.0, -0.5, 0.5, 0.2});
    }
    if (kind_ == Recalibration::kTakeUp || kind_ == Recalibration::kNarrowTakeUp) {
      // A take-up that absorbed a stiffening read K low (and tilted in depth)
      // and δ wide: the refit may undo all of it (δ down to 0, K up to 2.5×)
      // and move the take-up width w by a factor e^l, its prior the
      // identification's (a factor e) about the model's width, or about a
      // clearance's (kNarrowTakeUp).
      for (int j = 0; j < 2; ++j) {
        specs[std::size_t(j)].upper_bound = 1.5;
        specs[std::size_t(2 + j)].lower_bound = -model_->parameters().joints[j].backlash_rad;
      }
      for (int j = 0; j < 2; ++j) {
        const double w = model_->clearance_load_nm(j);
        const double narrow = std::min(0.0, std::log(NarrowTakeUpNm(model_->parameters().joints[j]) / w));
        const double start = kind_ == Recalibration::kNarrowTakeUp ? narrow : 0.0;
        specs.push_back({j == 0 ? "take_up1" : "take_up2", "", start,
                         std::min(std::log(0.01 / w), narrow - 1.0), std::log(2.0), 1.0});
      }
    }
    return specs;
  }
  /// K_j(L) as refitted, (1 + s_j)·K_j(L) tilted by u_j (rad/(N·m)).
  template <typename T>
  models::Vec2<T> Compliance(const T* p, double depth_m) const {
    models::Vec2<T> out;
    for (int j = 0; j < 2; ++j) {
      const auto& joint = model_->parameters().joints[j];
      // The law is read at the depth clamped to its range, as ComplianceAt does.
      const double depth = std::clamp(depth_m, joint.depth_min_m, joint.depth_max_m);
      const double k = models::ComplianceAt(joint, depth);
      const double per_tilt = per_tilt_[j][2] * depth + per_tilt_[j][3];
      const T u = kind_ != Recalibration::kScale ? p[4 + j] : T(0.0);
      const T tilted = joint.compliance.form == models::ComplianceForm::kInverseCubic
                           ? T(1.0) / (T(1.0 / k) + u * per_tilt)
                           : T(k) + u * per_tilt;
      out[j] = (T(1.0) + p[j]) * tilted;
    }
    return out;
  }
  template <typename T>
  models::Vec2<T> operator()(const T* p, const models::JointState<T>& state) const {
    using std::exp;
    using std::tanh;
    const models::Vec2<T> refitted = Compliance(p, ValueOf(state.insertion_depth_m));
    models::Vec2<T> out;
    for (int j = 0; j < 2; ++j) {
      const auto& joint = model_->parameters().joints[j];
      const double k = models::ComplianceAt(joint, ValueOf(state.insertion_depth_m));
      const T& tau = state.external_torque_nm[j];
      out[j] = (refitted[j] - T(k)) * tau;
      const double w = model_->clearance_load_nm(j);
      if (kind_ == Recalibration::kTakeUp || kind_ == Recalibration::kNarrowTakeUp) {
        // The model's dead zone replaced by one of clearance δ + d_j and width w·e^l_j.
        const double delta = joint.backlash_rad;
        out[j] += (T(delta) + p[2 + j]) * models::SmoothSaturation(tau / (T(w) * exp(p[6 + j]))) -
                  T(delta) * models::SmoothSaturation(tau / T(w));
      } else {
        out[j] += p[2 + j] * tanh(tau / T(w));
      }
    }
    return out;
  }

 private:
  const BaseModel* model_;
  Recalibration kind_;
  std::array<double, 4> per_tilt_[2];
};

// The rows of one segment (a push, a clamp) share what the model lacks: the
// cluster jackknife counts each segment as one draw, never below `floor`
// (the white-noise covariance). A short log holds a dozen segments, a few of
// which carry most of an effect's information: JackknifeSandwich in
// estimation/src/clustered_sandwich.h says why not the Liang–Zeger form.
Eigen::MatrixXd ClusteredBySegment(const Problem& problem, const std::vector<std::size_t>& samples,
                                   ceres::Problem* ceres_problem, const std::vector<double*>& blocks,
                                   ceres::ResidualBlockId residual_block,
                                   const Eigen::MatrixXd& floor) {
  std::vector<ceres::ResidualBlockId> rows;
  ceres_problem->GetResidualBlocks(&rows);
  // The samples' block first, then the priors (model-based rows).
  rows.erase(std::remove(rows.begin(), rows.end(), residual_block), rows.end());
  rows.insert(rows.begin(), residual_block);
  Eigen::SparseMatrix<double> jacobian;
  Eigen::VectorXd residuals;
  detail::EvaluateJacobian(ceres_problem, blocks, rows, &jacobian, &residuals);
  std::vector<int> cluster_of_row(std::size_t(residuals.size()), -1);
  for (std::size_t i = 0; i < samples.size(); ++i) {
    for (int j = 0; j < 2; ++j) cluster_of_row[2 * i + std::size_t(j)] = problem.samples[samples[i]].group;
  }
  try {
    const auto sandwich = detail::JackknifeSandwich(jacobian, residuals, cluster_of_row);
    if (sandwich.clusters < 2 || !sandwich.clustered.allFinite()) return floor;
    return detail::NotBelow(sandwich.clustered, floor);
  } catch (const std::runtime_error&) {
    return floor;  // a singular information matrix: the white-noise covariance stands
  }
}

}  // namespace

Term BaseRecalibrationTerm(const BaseModel& model, Recalibration kind) {
  const BaseRecalibration recalibration(model, kind);
  std::shared_ptr<const EffectModel> effect = MakeEffectModel(recalibration);
  Term term{effect, effect->DefaultParameters(), "base_recalibration", {}, {}};
  term.compliance = [recalibration](const double* p, double depth_m) {
    return Eigen::Vector2d(recalibration.Compliance(p, depth_m));
  };
  term.compliance_jet = [recalibration](const EffectJet* p, double depth_m) {
    return recalibration.Compliance(p, depth_m);
  };
  return term;
}

void SetRecalibration(const BaseModel& model, bool on, Problem* problem) {
  problem->refit.clear(), problem->added_refit.clear();
  if (!on) return;
  problem->refit = {BaseRecalibrationTerm(model, Recalibration::kScale)};
  problem->added_refit = {BaseRecalibrationTerm(model, Recalibration::kTilt)};
}

FitResult FitTerms(const Problem& problem, const BaseModel& model, const std::vector<Term>& fixed,
                   const std::vector<Term>& fitted, const std::vector<bool>& train_group,
                   bool covariance, double size_factor, bool clustered) {
  std::vector<std::size_t> samples;
  for (std::size_t i = 0; i < problem.samples.size(); ++i) {
    if (train_group[problem.samples[i].group]) samples.push_back(i);
  }
  std::vector<Term> terms = fixed;
  terms.insert(terms.end(), fitted.begin(), fitted.end());
  FitResult result;
  for (const Term& term : fitted) result.parameters.push_back(term.parameters);

  ceres::Problem::Options problem_options;
  problem_options.cost_function_ownership = ceres::TAKE_OWNERSHIP;
  ceres::Problem ceres_problem(problem_options);
  std::vector<double*> blocks;
  for (auto& values : result.parameters) blocks.push_back(values.data());
  const ceres::ResidualBlockId residual_block = ceres_problem.AddResidualBlock(
      new ResidualCost(problem, model, terms, fixed.size(), samples), nullptr, blocks);
  for (std::size_t t = 0; t < fitted.size(); ++t)
    AddEffectPrior(&ceres_problem, blocks[t], *fitted[t].effect);
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = 60;
  options.num_threads = 1;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &ceres_problem, &summary);
  if (!covariance) return result;

  ceres::Covariance::Options covariance_options;
  covariance_options.algorithm_type = ceres::DENSE_SVD;
  covariance_options.null_space_rank = -1;  // weakly identified shapes: pseudo-inverse
  ceres::Covariance ceres_covariance(covariance_options);
  std::vector<const double*> const_blocks(blocks.begin(), blocks.end());
  int total = 0;
  for (const auto& values : result.parameters) total += int(values.size());
  result.covariance = Eigen::MatrixXd::Zero(total, total);
  result.white_covariance = result.covariance;  // both stay zero if Ceres cannot invert
  if (ceres_covariance.Compute(const_blocks, &ceres_problem)) {
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> c(total, total);
    if (ceres_covariance.GetCovarianceMatrix(const_blocks, c.data())) {
      // Residuals beyond their noise model and autocorrelated samples both
      // make the nominal covariance too small.
      const double n = double(2 * samples.size());
      const double dispersion = std::max(1.0, 2.0 * summary.final_cost / std::max(1.0, n - total));
      result.covariance = c * dispersion / size_factor;
      result.white_covariance = result.covariance;
      if (clustered) result.covariance = ClusteredBySegment(problem, samples, &ceres_problem, blocks,
                                                            residual_block, result.covariance);
      result.covariance_ok = true;
    }
  }
  int offset = 0;
  for (const auto& values : result.parameters) {
    result.parameter_sd.emplace_back();
    for (std::size_t k = 0; k < values.size(); ++k, ++offset)
      result.parameter_sd.back().push_back(std::sqrt(std::max(0.0, result.covariance(offset, offset))));
  }
  return result;
}

std::array<double, 2> ContributionSizeMm(const Problem& problem, const BaseModel& model,
                                         const std::vector<Term>& fixed, const Term& term,
                                         const Eigen::MatrixXd& covariance) {
  std::vector<Term> with = fixed;
  with.push_back(term);
  const int m = int(term.parameters.size());
  const std::size_t n = problem.samples.size();
  // The change of each sample's residual and its derivative by each parameter
  // (8 at a time), profiled per held run like the residual itself.
  std::vector<Eigen::Vector2d> change(n, Eigen::Vector2d::Zero());
  std::vector<std::vector<Eigen::Vector2d>> derivative(
      m, std::vector<Eigen::Vector2d>(n, Eigen::Vector2d::Zero()));
  std::vector<std::vector<EffectJet>> jets;
  for (const Term& t : with) jets.emplace_back(t.parameters.begin(), t.parameters.end());
  for (int start = 0; start < std::max(m, 1); start += kEffectJetSize) {
    auto seeded = jets;
    for (int k = start; k < std::min(m, start + kEffectJetSize); ++k) seeded.back()[k].v[k - start] = 1.0;
    std::vector<const EffectJet*> pointers;
    for (const auto& block : seeded) pointers.push_back(block.data());
    const std::vector<const EffectJet*> base_pointers(pointers.begin(), pointers.end() - 1);
    for (std::size_t i = 0; i < n; ++i) {
      const Sample& s = problem.samples[i];
      const auto a = ModelResidual<EffectJet>(s, model, fixed, base_pointers);
      const auto b = ModelResidual<EffectJet>(s, model, with, pointers);
      for (int j = 0; j < 2; ++j) {
        if (!s.used[j]) continue;
        change[i][j] = (a[j] - b[j]).a;
        for (int k = start; k < std::min(m, start + kEffectJetSize); ++k)
          derivative[k][i][j] = (a[j] - b[j]).v[k - start];
      }
    }
  }
  ProfileGroups(problem, change);
  for (auto& column : derivative) ProfileGroups(problem, column);
  // size² = Σ_j mean over joint j's used samples of (change · mm/rad)².
  double square = 0.0;
  Eigen::VectorXd gradient = Eigen::VectorXd::Zero(m);
  for (int j = 0; j < 2; ++j) {
    double count = 0.0;
    for (const Sample& s : problem.samples) count += s.used[j] ? 1.0 : 0.0;
    if (count == 0.0) continue;
    for (std::size_t i = 0; i < n; ++i) {
      const Sample& s = problem.samples[i];
      if (!s.used[j]) continue;
      const double k2 = s.mm_per_rad[j] * s.mm_per_rad[j] / count;
      square += k2 * change[i][j] * change[i][j];
      for (int k = 0; k < m; ++k) gradient[k] += 2.0 * k2 * change[i][j] * derivative[k][i][j];
    }
  }
  const double size = std::sqrt(square);
  if (!(size > 0.0) || covariance.rows() != m) return {size, 0.0};
  gradient /= 2.0 * size;  // d sqrt(S) = dS / (2 sqrt(S))
  return {size, std::sqrt(std::max(0.0, double(gradient.transpose() * covariance * gradient)))};
}

}  // namespace pliant::estimation::diagnosis
