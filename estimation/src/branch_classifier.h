#pragma once
// Which wall the shaft bears on, sample by sample: the branch of the paper's
// Fig. 5. Shared by the paper's procedure and the identifiability checks.

#include <map>
#include <vector>

#include "pliant/estimation/identification_data.h"
#include "pliant/models/parameters.h"

namespace pliant::estimation::detail {

/// +1 (loaded positive), −1 (loaded negative) or 0 (inside the clearance, or
/// tip free) for joint j of every sample. The reference effort is tau0(q) of
/// `bias` when the data hold free-tip rows (the bias was measured), otherwise
/// the median effort of the segment (a sweep is loaded both ways about equally).
struct BranchClassifier {
  BranchClassifier(const IdentificationData& data, const models::ModelParameters& bias,
                   const std::array<double, 2>& threshold_nm);

  std::vector<int> side[2];                   ///< per sample
  std::vector<double> reference_effort_nm[2];  ///< per sample
  bool bias_measured = false;
};

/// Depth rounded to `resolution_m`, as a key.
inline long DepthKey(double depth_m, double resolution_m) {
  return long(depth_m / resolution_m + 0.5);
}

}  // namespace pliant::estimation::detail
