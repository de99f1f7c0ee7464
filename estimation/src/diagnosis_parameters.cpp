// The parameters with fitted catalogue effects (pliant diagnose --write-params,
// pliant identify --effect), for every consumer that reads a parameters file
// (correct, the filter, the smoother, the next diagnosis).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "diagnosis_internal.h"
#include "pliant/estimation/diagnosis.h"
#include "pliant/estimation/effect_fit.h"

namespace pliant::estimation {
namespace diagnosis {

std::array<double, 4> CompliancePerTilt(const models::JointParameters& joint) {
  const double middle = 0.5 * (joint.depth_min_m + joint.depth_max_m);
  const double half = 0.5 * (joint.depth_max_m - joint.depth_min_m);
  const double k_middle = models::ComplianceAt(joint, middle);
  // u·x = u·(L − L_mid)/half on 1/K (divided by K_mid) or on K (times K_mid):
  // the linear and constant coefficients of the cubic.
  switch (joint.compliance.form) {
    case models::ComplianceForm::kInverseCubic:
      return {0.0, 0.0, -1.0 / (k_middle * half), middle / (k_middle * half)};
    case models::ComplianceForm::kDirectCubic:
      return {0.0, 0.0, k_middle / half, -k_middle * middle / half};
    case models::ComplianceForm::kBeamSeries:
      break;
  }
  return {0.0, 0.0, 0.0, 0.0};
}

}  // namespace diagnosis
namespace {

// The recalibration's parameters: s1, s2, d1, d2, then the depth tilts u1, u2.
double Tilt(const EffectFinding& r, int joint) {
  return r.parameters.size() > std::size_t(4 + joint) ? r.parameters[std::size_t(4 + joint)] : 0.0;
}

std::string Formatted(const char* format, double a, double b) {
  char text[160];
  std::snprintf(text, sizeof text, format, a, b);
  return text;
}

void Append(std::string* text, const std::string& more) {
  *text += (text->empty() ? "" : "; ") + more;
}

// Index of a law coefficient's field ("compliance.c3", …) in the stored
// coefficients, −1 for anything else (the beam series' cannula length is
// geometry and does not scale).
int LawCoefficient(const std::string& field) {
  static const char* kNames[2][4] = {
      {"compliance.c3", "compliance.c2", "compliance.c1", "compliance.c0"},
      {"compliance.joint_compliance_rad_per_nm", "compliance.structure_compliance_rad_per_n",
       "compliance.shaft_flexibility_per_nm2", ""}};
  for (const auto& form : kNames) {
    for (int i = 0; i < 4; ++i) {
      if (field == form[i]) return i;
    }
  }
  return -1;
}

// Drops the covariance's rows and columns of an effect about to be refitted.
void DropEffect(models::ParameterCovariance* c, const std::string& effect) {
  std::vector<Eigen::Index> keep;
  for (std::size_t i = 0; i < c->names.size(); ++i) {
    if (c->names[i].rfind(effect + ".", 0) != 0) keep.push_back(Eigen::Index(i));
  }
  models::ParameterCovariance kept;
  kept.matrix.resize(Eigen::Index(keep.size()), Eigen::Index(keep.size()));
  for (std::size_t a = 0; a < keep.size(); ++a) {
    kept.names.push_back(c->names[std::size_t(keep[a])]);
    for (std::size_t b = 0; b < keep.size(); ++b)
      kept.matrix(Eigen::Index(a), Eigen::Index(b)) = c->matrix(keep[a], keep[b]);
  }
  *c = std::move(kept);
}

// K tilted in depth by u_j (CompliancePerTilt), then K → (1 + s_j)·K, and
// δ → δ + d_j, in the values and their sources.
void ApplyRecalibration(const EffectFinding& r, const std::string& provenance,
                        models::ModelParameters* p) {
  for (int j = 0; j < 2; ++j) {
    auto& joint = p->joints[std::size_t(j)];
    const auto per_tilt = diagnosis::CompliancePerTilt(joint);
    for (int k = 0; k < 4; ++k)
      joint.compliance.cubic.coefficients[std::size_t(k)] += Tilt(r, j) * per_tilt[std::size_t(k)];
    const double scale = 1.0 + r.parameters[std::size_t(j)];
    const double widening = r.parameters[std::size_t(2 + j)];
    const double widening_sd = r.parameter_sd.size() > std::size_t(2 + j) ? r.parameter_sd[2 + j] : 0.0;
    models::ScaleCompliance(joint.compliance, scale);
    // A clearance cannot be negative: what a narrower fit asks beyond 0 is not physical.
    joint.backlash_rad = std::max(0.0, joint.backlash_rad + widening);
    if (r.parameters.size() > std::size_t(6 + j)) {  // the take-up refitted: its width too
      joint.deadzone_width_nm = diagnosis::ClearanceLoad(joint) * std::exp(r.parameters[6 + j]);
      Append(&joint.sources["deadzone_width_nm"],
             Formatted("refitted to %.4g N·m%.0s", joint.deadzone_width_nm, 0.0) + " by " + provenance);
    }
    Append(&joint.sources["compliance"],
           Formatted("tilted in depth by %+.4f, scaled by %.4f", Tilt(r, j), scale) + " by " +
               provenance);
    Append(&joint.sources["backlash_rad"],
           Formatted("widened by %+.6f ± %.6f rad", widening, widening_sd) + " by " + provenance);
  }
}

// The file's covariance after the fit, to first order: the law's coefficients
// c' = (c + u·a)·(1 + s)^∓1 (a = CompliancePerTilt of the given law; 1/K's
// cubic divides, the direct forms multiply) and δ' = δ + d move with the
// refit, and the effects' parameters join the list. With G = ∂(file's
// parameters)/∂(fitted parameters) and D the scaling, C' = D C D + G Σ Gᵀ
// over the old names followed by the effects'.
void ExtendCovariance(const models::ModelParameters& given, const models::ModelParameters& scaled,
                      const FittedEffects& fitted, models::ParameterCovariance* c) {
  const Eigen::Index fit_size = fitted.covariance.rows();
  const Eigen::Index offset =
      fitted.recalibration ? Eigen::Index(fitted.recalibration->parameters.size()) : 0;
  const Eigen::Index old_size = Eigen::Index(c->names.size());
  Eigen::Index effect_size = 0;
  for (const auto& e : fitted.effects) effect_size += Eigen::Index(e.parameters.size());
  if (fit_size != offset + effect_size) return;  // no covariance from the fit: sd only
  Eigen::VectorXd scale = Eigen::VectorXd::Ones(old_size + effect_size);
  Eigen::MatrixXd g = Eigen::MatrixXd::Zero(old_size + effect_size, fit_size);
  for (Eigen::Index i = 0; i < old_size && fitted.recalibration; ++i) {
    const std::string& name = c->names[std::size_t(i)];
    if (name.rfind("joint", 0) != 0 || name.size() < 8) continue;
    const int j = name[5] - '1';
    if (j < 0 || j > 1) continue;
    const auto& law = scaled.joints[std::size_t(j)].compliance;
    const double share = fitted.recalibration->parameters[std::size_t(j)];
    const int k = LawCoefficient(name.substr(7));
    if (k >= 0) {
      const bool inverse = law.form == models::ComplianceForm::kInverseCubic;
      scale[i] = inverse ? 1.0 / (1.0 + share) : 1.0 + share;
      g(i, j) = (inverse ? -1.0 : 1.0) * law.cubic.coefficients[std::size_t(k)] / (1.0 + share);
      if (offset > 4 + j)
        g(i, 4 + j) = diagnosis::CompliancePerTilt(given.joints[std::size_t(j)])[std::size_t(k)] *
                      scale[i];
    }
    if (name.substr(7) == "backlash_rad") g(i, 2 + j) = 1.0;
    if (name.substr(7) == "deadzone_width_nm" && offset > 6 + j) {
      scale[i] = 0.0;  // w' = w·e^l: the refit's l alone
      g(i, 6 + j) = scaled.joints[std::size_t(j)].deadzone_width_nm;
    }
  }
  for (Eigen::Index k = 0; k < effect_size; ++k) g(old_size + k, offset + k) = 1.0;
  Eigen::MatrixXd old = Eigen::MatrixXd::Zero(old_size + effect_size, old_size + effect_size);
  old.topLeftCorner(old_size, old_size) = c->matrix;
  c->matrix = scale.asDiagonal() * old * scale.asDiagonal() + g * fitted.covariance * g.transpose();
  for (const auto& e : fitted.effects) {
    for (const auto& parameter : e.parameter_names) c->names.push_back(e.name + "." + parameter);
  }
}

}  // namespace

models::ModelParameters WithFittedEffects(const models::ModelParameters& parameters,
                                          const FittedEffects& fitted,
                                          const std::string& provenance) {
  models::ModelParameters p = parameters;
  if (!p.covariance) p.covariance = models::ParameterCovariance{};
  for (const EffectFinding& e : fitted.effects) DropEffect(&*p.covariance, e.name);
  if (fitted.recalibration) ApplyRecalibration(*fitted.recalibration, provenance, &p);
  ExtendCovariance(parameters, p, fitted, &*p.covariance);
  if (p.covariance->names.empty()) p.covariance.reset();
  std::string names;
  for (const EffectFinding& e : fitted.effects) {
    models::EffectParameters effect;
    effect.name = e.name;
    effect.parameter_names = e.parameter_names;
    effect.values = e.parameters;
    effect.sd = e.parameter_sd;
    effect.sd.resize(effect.values.size(), 0.0);
    // Replace an effect of the same name the file already carried.
    p.effects.erase(std::remove_if(p.effects.begin(), p.effects.end(),
                                   [&](const models::EffectParameters& old) { return old.name == e.name; }),
                    p.effects.end());
    p.effects.push_back(std::move(effect));
    names += (names.empty() ? "" : " + ") + e.name;
  }
  Append(&p.description, "with " + names + " fitted by " + provenance);
  return p;
}

models::ModelParameters WithDiagnosedEffects(const models::ModelParameters& parameters,
                                             const Diagnosis& diagnosis, const std::string& source) {
  return WithFittedEffects(parameters,
                           {diagnosis.added, diagnosis.recalibration, diagnosis.added_covariance},
                           "pliant diagnose on " + source);
}

}  // namespace pliant::estimation
