// pliant identify --effect: the summary's lines (identify_effects.h).
#include "identify_effects.h"

#include <cstdio>

namespace pliant::cli {
namespace {

std::string ParametersText(const estimation::EffectFinding& e) {
  char line[160];
  std::string text = "    " + e.name + ":";
  for (std::size_t k = 0; k < e.parameters.size(); ++k) {
    std::snprintf(line, sizeof line, " %s = %.4g ± %.2g", e.parameter_names[k].c_str(),
                  e.parameters[k], k < e.parameter_sd.size() ? e.parameter_sd[k] : 0.0);
    text += line;
  }
  return text + "\n";
}

std::string HeldText(const estimation::LogEffectFit& fit) {
  char line[320];
  std::snprintf(line, sizeof line,
                "  effects fitted on the held tip of %s (%zu samples, %d segments), with each "
                "joint's compliance scale and clearance:\n",
                JoinedPaths(fit.logs).c_str(), fit.samples, fit.segments);
  std::string text = line;
  for (const auto& e : fit.fitted.effects) text += ParametersText(e);
  std::snprintf(line, sizeof line,
                "    held-out RMS error at the tip: %.3f mm as identified, %.3f mm with K and δ "
                "refitted, %.3f mm with the effects\n",
                fit.rms_given_mm, fit.rms_refit_mm, fit.rms_with_effects_mm);
  text += line;
  for (const auto& note : fit.notes) text += "    note: " + note + "\n";
  return text;
}

std::string FreeText(const estimation::FreeMotionFit& fit) {
  char line[320];
  std::snprintf(line, sizeof line,
                "  the arm's dynamics fitted on the free motion of %s (%zu rows; σ over %d blocks "
                "of %.1f s, the residual's correlation time %.2f s):\n",
                JoinedPaths(fit.logs).c_str(), fit.rows, fit.blocks, fit.block_s, fit.correlation_s);
  std::string text = line;
  for (const auto& e : fit.fitted.effects) text += ParametersText(e);
  std::snprintf(line, sizeof line,
                "    effort beyond the bias table, RMS: %.3f / %.3f N·m, with the effects %.3f / "
                "%.3f N·m\n",
                fit.rms_before_nm[0], fit.rms_before_nm[1], fit.rms_after_nm[0],
                fit.rms_after_nm[1]);
  text += line;
  for (const auto& note : fit.notes) text += "    note: " + note + "\n";
  return text;
}

}  // namespace

std::string EffectFitsText(const EffectFits& fits) {
  return (fits.free_motion ? FreeText(*fits.free_motion) : "") + (fits.held ? HeldText(*fits.held) : "");
}

}  // namespace pliant::cli
