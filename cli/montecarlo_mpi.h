#pragma once
// `pliant montecarlo` under mpirun (Boost.MPI over OpenMPI). Kept out of the
// libraries: a single-machine run never initialises MPI.

#include <nlohmann/json.hpp>

#include "pliant/experiments/montecarlo.h"

namespace pliant::cli {

/// True when this process was started by mpirun (OpenMPI or PMIx sets its rank).
bool LaunchedByMpirun();

/// Rank 0 resumes DIR and hands out the pending trials by position
/// (pending[i] to rank i mod size); every rank runs its share on
/// options.threads threads (1 when 0); rows go to rank 0, which appends them
/// to DIR/trials.csv as they come and writes the outputs. Returns the summary
/// on rank 0, null elsewhere.
nlohmann::json RunMontecarloMpi(const experiments::Study& study,
                                const experiments::MontecarloOptions& options);

}  // namespace pliant::cli
