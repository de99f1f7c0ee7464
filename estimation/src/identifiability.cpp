// What a set of logs cannot determine, and why, in words a user can act on.
#include <cstdio>
#include <map>
#include <set>

#include "branch_classifier.h"
#include "identification_common.h"
#include "pliant/estimation/identification.h"

namespace pliant::estimation {
namespace {

std::size_t FreeTipSamples(const IdentificationData& data) {
  std::size_t free_samples = 0;
  for (const auto& s : data.samples) free_samples += !s.tip_fixed;
  return free_samples;
}

// Per joint: the depths at which the held tip was loaded past tau_min, and
// whether one tip_fixed segment loaded the joint both ways (a reversal: the
// shaft crossed its clearance while the tip stayed put, which is what shows δ).
struct JointLoads {
  std::set<long> depths;
  bool reversal = false;
};

std::array<JointLoads, 2> ClassifyLoads(const IdentificationData& data,
                                        const models::ModelParameters& bias,
                                        const PaperProcedureOptions& options) {
  std::array<JointLoads, 2> out;
  if (data.CountTipFixed() == 0) return out;
  const detail::BranchClassifier branches(data, bias, options.contact_threshold_nm);
  for (int j = 0; j < 2; ++j) {
    std::map<int, std::set<int>> sides_in_segment;
    for (std::size_t i = 0; i < data.samples.size(); ++i) {
      const int side = branches.side[j][i];
      if (side == 0) continue;
      sides_in_segment[data.samples[i].segment].insert(side);
      out[j].depths.insert(
          detail::DepthKey(data.samples[i].insertion_depth_m, options.depth_resolution_m));
    }
    for (const auto& [segment, sides] : sides_in_segment) out[j].reversal |= sides.size() == 2;
  }
  return out;
}

}  // namespace

namespace detail {

UndeterminedParameters FindUndetermined(const IdentificationData& data,
                                        const models::ModelParameters& bias,
                                        const PaperProcedureOptions& options) {
  UndeterminedParameters out;
  const auto loads = ClassifyLoads(data, bias, options);
  const bool no_bias_sweep = FreeTipSamples(data) == 0;
  // Without any held tip nothing measures K or delta: they keep their prior
  // as they are, with nothing to carry their uncertainty into.
  const bool held_tip = data.CountTipFixed() > 0;
  for (int j = 0; j < 2; ++j) {
    out.bias[j] = no_bias_sweep;
    out.backlash[j] = held_tip && !loads[j].reversal;
  }
  return out;
}

}  // namespace detail

std::vector<std::string> IdentifiabilityWarnings(const IdentificationData& data,
                                                 const models::ModelParameters& bias,
                                                 const PaperProcedureOptions& options,
                                                 int law_coefficients) {
  std::vector<std::string> warnings;
  if (data.CountTipFixed() == 0) {
    warnings.push_back(
        "no tip_fixed samples: compliance K1(L), K2(L), backlash delta1, delta2 and the dead-zone "
        "widths cannot be identified (the encoders see the shaft bend only while the tip is held, "
        "by a clamp or a divot); they keep their prior");
  }
  if (FreeTipSamples(data) == 0) {
    warnings.push_back(
        "no free-tip samples (no bias sweep): the bias torque tau0(q) is not measured (a held tip "
        "cannot tell its slope from 1/K, nor its level from the tip angle); it keeps its prior — "
        "record a bias sweep (the paper's Fig. 4 protocol) to measure it");
  }
  if (data.CountTipFixed() == 0) return warnings;

  const auto loads = ClassifyLoads(data, bias, options);
  for (int j = 0; j < 2; ++j) {
    const std::string joint = std::to_string(j + 1);
    const auto& depths = loads[j].depths;
    if (depths.empty()) {
      char text[300];
      std::snprintf(text, sizeof text,
                    "joint %s: the held tip is never loaded beyond %.2f N·m: K%s(L) and delta%s "
                    "cannot be identified; they keep their prior",
                    joint.c_str(), options.contact_threshold_nm[j], joint.c_str(), joint.c_str());
      warnings.push_back(text);
      continue;
    }
    if (!loads[j].reversal) {
      warnings.push_back("joint " + joint + ": no direction reversals (no tip_fixed segment loads "
                         "joint " + joint + " both ways): backlash delta" + joint +
                         " cannot be told from the tip position, so it keeps its prior — load the "
                         "held tip both ways within one segment (a clamped-beam sweep) to "
                         "measure it");
    }
    if (int(depths.size()) < law_coefficients) {
      char text[400];
      std::snprintf(text, sizeof text,
                    "joint %s: loaded at %zu depth(s) only, from %.3f m: the depth law of K%s(L) "
                    "(%d coefficients) cannot be determined; K%s at %s is identified, the law's "
                    "shape keeps its prior",
                    joint.c_str(), depths.size(),
                    double(*depths.begin()) * options.depth_resolution_m, joint.c_str(),
                    law_coefficients, joint.c_str(),
                    depths.size() == 1 ? "that depth" : "those depths");
      warnings.push_back(text);
    }
  }
  return warnings;
}

}  // namespace pliant::estimation
