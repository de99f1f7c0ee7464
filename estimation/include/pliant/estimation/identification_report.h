#pragma once
// What `pliant identify` and `pliant params` print: a table for a person and
// the same content as JSON for programs.

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "pliant/estimation/compliance_law_fit.h"
#include "pliant/estimation/free_motion_fit.h"
#include "pliant/estimation/identification.h"
#include "pliant/estimation/parameter_query.h"

namespace pliant::estimation {

/// Per-joint comparison of the three compliance laws on the per-depth
/// estimates (empty for a joint with fewer than 5 depths).
std::array<std::vector<LawComparison>, 2> CompareLaws(const IdentificationResult& result,
                                                      double cannula_length_m = 0.025);

/// Each estimated parameter ± σ, K(L) at three depths, fit RMS per joint, the
/// condition number, the law comparison and the identifiability warnings.
std::string IdentificationTable(const IdentificationResult& result,
                                const IdentificationData& data,
                                const std::array<std::vector<LawComparison>, 2>& laws);

/// Fitted effects as [{"name", "parameters": [{"name", "value", "sd"}]}].
nlohmann::json EffectFindingsJson(const std::vector<EffectFinding>& findings);

/// `pliant identify --json`'s "free_motion_fit" (and pliant.identify_arm_dynamics's report):
/// the logs, rows, blocks, the effort's RMS before and after, each effect's values ± sd.
nlohmann::json FreeMotionFitJson(const FreeMotionFit& fit);

nlohmann::json IdentificationJson(const IdentificationResult& result,
                                  const IdentificationData& data,
                                  const std::array<std::vector<LawComparison>, 2>& laws);

/// {"depth_m", "K1", "K1_sd", "K2", "K2_sd", "delta1", "delta1_sd", "delta2",
/// "delta2_sd", "inverse_K1", …, "depth_clamped"} (K in rad/(N·m), δ in rad).
nlohmann::ordered_json DepthJson(const ParametersAtDepth& at);
std::string DepthTable(const ParametersAtDepth& at);

}  // namespace pliant::estimation
