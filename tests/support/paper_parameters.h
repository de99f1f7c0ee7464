#pragma once
// The paper's parameters for tests: the library's single copy of them.
#include "pliant/models/paper_parameters.h"

namespace pliant::models::testing {

inline ModelParameters PaperParameters() { return models::PaperParameters(); }

}  // namespace pliant::models::testing
