// pliant diagnose --write-params: the parameters with what the diagnosis
// fitted, for every consumer that reads a parameters file (correct, the
// filter, the smoother, the next diagnosis).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "pliant/estimation/diagnosis.h"

namespace pliant::estimation {
namespace {

// Factor by which a law's stored coefficients change when K is scaled by
// `scale`: 1/K's cubic divides, the direct forms multiply.
double CoefficientFactor(models::ComplianceForm form, double scale) {
  return form == models::ComplianceForm::kInverseCubic ? 1.0 / scale : scale;
}

std::string Formatted(const char* format, double a, double b) {
  char text[160];
  std::snprintf(text, sizeof text, format, a, b);
  return text;
}

void Append(std::string* text, const std::string& more) {
  *text += (text->empty() ? "" : "; ") + more;
}

// The law's coefficients' rows and columns scale with them (a linear map);
// the clearance's variance grows by the refit's. The beam series' cannula
// length is geometry and does not scale.
void ScaleCovariance(models::ModelParameters* p, int joint, double factor, double clearance_var) {
  if (!p->covariance) return;
  auto& c = *p->covariance;
  const std::string law = "joint" + std::to_string(joint + 1) + ".compliance.";
  const std::string delta = "joint" + std::to_string(joint + 1) + ".backlash_rad";
  for (std::size_t i = 0; i < c.names.size(); ++i) {
    const std::string& name = c.names[i];
    if (name.rfind(law, 0) == 0 && name != law + "cannula_length_m") {
      c.matrix.row(Eigen::Index(i)) *= factor;
      c.matrix.col(Eigen::Index(i)) *= factor;
    }
    if (name == delta) c.matrix(Eigen::Index(i), Eigen::Index(i)) += clearance_var;
  }
}

void ApplyRecalibration(const EffectFinding& r, const std::string& source,
                        models::ModelParameters* p) {
  for (int j = 0; j < 2; ++j) {
    auto& joint = p->joints[std::size_t(j)];
    const double scale = 1.0 + r.parameters[std::size_t(j)];
    const double widening = r.parameters[std::size_t(2 + j)];
    const double widening_sd = r.parameter_sd.size() > std::size_t(2 + j) ? r.parameter_sd[2 + j] : 0.0;
    models::ScaleCompliance(joint.compliance, scale);
    // A clearance cannot be negative: what a narrower fit asks beyond 0 is not physical.
    joint.backlash_rad = std::max(0.0, joint.backlash_rad + widening);
    ScaleCovariance(p, j, CoefficientFactor(joint.compliance.form, scale), widening_sd * widening_sd);
    Append(&joint.sources["compliance"],
           Formatted("scaled by %.4f by pliant diagnose", scale, 0.0) + " on " + source);
    Append(&joint.sources["backlash_rad"],
           Formatted("widened by %+.6f ± %.6f rad by pliant diagnose", widening, widening_sd) +
               " on " + source);
  }
}

}  // namespace

models::ModelParameters WithDiagnosedEffects(const models::ModelParameters& parameters,
                                             const Diagnosis& diagnosis, const std::string& source) {
  models::ModelParameters p = parameters;
  if (diagnosis.recalibration) ApplyRecalibration(*diagnosis.recalibration, source, &p);
  std::string names;
  for (const EffectFinding& e : diagnosis.added) {
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
  Append(&p.description, "with " + names + " fitted by pliant diagnose on " + source);
  return p;
}

}  // namespace pliant::estimation
