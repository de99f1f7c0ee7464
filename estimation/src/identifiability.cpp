// What a set of logs cannot determine, and why, in words a user can act on.
#include <cstdio>
#include <map>
#include <set>

#include "branch_classifier.h"
#include "pliant/estimation/identification.h"

namespace pliant::estimation {

std::vector<std::string> IdentifiabilityWarnings(const IdentificationData& data,
                                                 const models::ModelParameters& bias,
                                                 const PaperProcedureOptions& options,
                                                 int law_coefficients) {
  std::vector<std::string> warnings;
  const auto& samples = data.samples;
  std::size_t free_rows = 0;
  for (const auto& s : samples) free_rows += !s.tip_fixed;
  if (data.CountTipFixed() == 0) {
    warnings.push_back(
        "no tip_fixed samples: compliance K1(L), K2(L), backlash delta1, delta2 and the dead-zone "
        "widths cannot be identified (the encoders see the shaft bend only while the tip is held, "
        "by a clamp or a divot); they keep their prior");
  }
  if (free_rows == 0) {
    warnings.push_back(
        "no free-tip samples: the bias torque tau0(q) is not measured over the joint range (a "
        "bias sweep is); it keeps its prior away from the held angles");
  }
  if (data.CountTipFixed() == 0) return warnings;

  const detail::BranchClassifier branches(data, bias, options.contact_threshold_nm);
  for (int j = 0; j < 2; ++j) {
    const std::string joint = std::to_string(j + 1);
    std::map<int, std::set<int>> sides_in_segment;
    std::set<long> depths;
    for (std::size_t i = 0; i < samples.size(); ++i) {
      const int side = branches.side[j][i];
      if (side == 0) continue;
      sides_in_segment[samples[i].segment].insert(side);
      depths.insert(detail::DepthKey(samples[i].insertion_depth_m, options.depth_resolution_m));
    }
    if (depths.empty()) {
      char text[300];
      std::snprintf(text, sizeof text,
                    "joint %s: the held tip is never loaded beyond %.2f N·m: K%s(L) and delta%s "
                    "cannot be identified; they keep their prior",
                    joint.c_str(), options.contact_threshold_nm[j], joint.c_str(), joint.c_str());
      warnings.push_back(text);
      continue;
    }
    bool reversal = false;
    for (const auto& [segment, sides] : sides_in_segment) reversal |= sides.size() == 2;
    if (!reversal) {
      warnings.push_back("joint " + joint + ": no direction reversals (no tip_fixed segment loads "
                         "joint " + joint + " both ways): backlash delta" + joint +
                         " cannot be told from the tip position, so it keeps its prior");
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
