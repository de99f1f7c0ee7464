#pragma once
// The σ a parameters file states for one named parameter (its covariance's
// diagonal), for tests that check an estimate against its truth.

#include <algorithm>
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "pliant/models/parameters.h"

namespace pliant::testing {

/// sqrt of the covariance's diagonal at `name`; NaN (and a test failure) when
/// the file has no covariance or does not name it.
inline double NamedSd(const models::ModelParameters& p, const std::string& name) {
  if (!p.covariance) {
    ADD_FAILURE() << "no covariance";
    return std::nan("");
  }
  const auto& names = p.covariance->names;
  const auto k = long(std::find(names.begin(), names.end(), name) - names.begin());
  if (k == long(names.size())) {
    ADD_FAILURE() << name << " is not in the covariance";
    return std::nan("");
  }
  return std::sqrt(p.covariance->matrix(k, k));
}

}  // namespace pliant::testing
