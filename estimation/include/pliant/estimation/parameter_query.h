#pragma once
// "What is my compliance at 12 cm?": the parameters at one depth, each with
// its standard deviation, from a parameters file's covariance (first-order
// propagation through the compliance law, with exact derivatives).

#include <array>

#include "pliant/models/parameters.h"

namespace pliant::estimation {

struct JointAtDepth {
  double compliance_rad_per_nm = 0.0;        ///< K(L)
  double compliance_sd = 0.0;                ///< 0 when the file has no covariance for it
  double inverse_compliance_nm_per_rad = 0.0;  ///< 1/K(L), the paper's Fig. 6 axis
  double inverse_compliance_sd = 0.0;
  double backlash_rad = 0.0;
  double backlash_sd = 0.0;
  bool depth_clamped = false;  ///< L was outside the valid range: K is the nearest end's
  /// The file's covariance holds this joint's law: false for a joint no log
  /// of the identification recorded (its K kept the prior's value, its σ
  /// shown as 0 is not known).
  bool in_covariance = false;
};

struct ParametersAtDepth {
  double insertion_depth_m = 0.0;
  std::array<JointAtDepth, 2> joints;
};

/// Parameters must pass models::ValidateParameters.
ParametersAtDepth QueryParametersAtDepth(const models::ModelParameters& parameters,
                                         double insertion_depth_m);

}  // namespace pliant::estimation
