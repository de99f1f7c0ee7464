// `pliant montecarlo` across MPI ranks. Rank 0 owns DIR: it resumes, hands
// out the pending trials, appends every row as it arrives (its own threads'
// and the other ranks') and writes the outputs; the summary is the same
// function of the same rows as on one machine.
#include <chrono>
#include <cstdlib>
#include <exception>
#include <mutex>
#include <thread>

#include <boost/mpi.hpp>
#include <boost/serialization/string.hpp>
#include <boost/serialization/vector.hpp>

#include "montecarlo_mpi.h"
#include "pliant/io/input_error.h"
#include "pliant/io/progress.h"

namespace pliant::cli {
namespace {

namespace mpi = boost::mpi;
using experiments::TrialResult;

enum Tag { kRow = 1, kDone = 2 };

}  // namespace

bool LaunchedByMpirun() {
  return std::getenv("OMPI_COMM_WORLD_SIZE") != nullptr || std::getenv("PMIX_RANK") != nullptr;
}

nlohmann::json RunMontecarloMpi(const experiments::Study& study,
                                const experiments::MontecarloOptions& options) {
  mpi::environment environment(mpi::threading::serialized, /*abort_on_exception=*/false);
  mpi::communicator world;
  const int rank = world.rank(), size = world.size();
  const int trials = options.trials > 0 ? options.trials : study.trials;
  int threads = options.threads > 0 ? options.threads : 1;
  // Worker threads send rows themselves (one at a time, under RunTrials' lock).
  if (rank != 0 && environment.thread_level() < mpi::threading::serialized) threads = 1;

  // Rank 0 opens DIR; a problem there (another study's trials) stops every rank.
  std::unique_ptr<experiments::TrialsFile> file;
  std::string problem;
  std::exception_ptr open_failure;
  std::vector<int> pending;
  if (rank == 0) {
    try {
      file = std::make_unique<experiments::TrialsFile>(options.output_dir, study);
      pending = file->Pending(trials);
    } catch (const std::exception& e) {
      problem = e.what();
      open_failure = std::current_exception();
    }
  }
  mpi::broadcast(world, problem, 0);
  if (!problem.empty()) {
    if (open_failure) std::rethrow_exception(open_failure);
    throw io::InputError("rank " + std::to_string(rank), 0, 0, "rank 0 stopped: " + problem,
                         "see rank 0's message");
  }
  mpi::broadcast(world, pending, 0);
  std::vector<int> mine;
  for (std::size_t i = rank; i < pending.size(); i += size) mine.push_back(pending[i]);

  const double start = experiments::Now();
  if (rank != 0) {
    std::string failure;
    try {
      experiments::RunTrials(study, mine, threads, [&](const TrialResult& r) {
        world.send(0, kRow, experiments::FormatTrialRow(r));
      });
    } catch (const std::exception& e) {
      failure = e.what();
    }
    world.send(0, kDone, failure);
    return nullptr;
  }

  std::mutex mutex;  // the file and the bar, shared by rank 0's workers and its receiver
  io::Progress progress("pliant montecarlo", "trials", trials);
  progress.Set(trials - static_cast<double>(pending.size()));
  std::exception_ptr own_failure;
  std::thread workers([&] {
    try {
      experiments::RunTrials(study, mine, threads, [&](const TrialResult& r) {
        const std::lock_guard<std::mutex> lock(mutex);
        file->Append(r);
        progress.Add();
      });
    } catch (...) {
      own_failure = std::current_exception();
    }
  });
  std::string failure;
  for (int done = 1; done < size;) {
    // Poll, not a blocking receive: OpenMPI's receive spins a core, which
    // rank 0's own worker threads need.
    const auto probe = world.iprobe(mpi::any_source, mpi::any_tag);
    if (!probe) {
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
      continue;
    }
    std::string message;
    const mpi::status status = world.recv(probe->source(), probe->tag(), message);
    if (status.tag() == kDone) {
      ++done;
      if (!message.empty() && failure.empty()) {
        failure = "rank " + std::to_string(status.source()) + ": " + message;
      }
      continue;
    }
    const auto row = experiments::ParseTrialRow(message);
    const std::lock_guard<std::mutex> lock(mutex);
    if (row) file->Append(*row), progress.Add();
  }
  workers.join();
  if (own_failure) std::rethrow_exception(own_failure);
  if (!failure.empty()) throw std::runtime_error(failure);
  const auto timing = experiments::TimingJson(threads, size, trials, pending.size(), experiments::Now() - start);
  return experiments::FinishStudy(study, trials, *file, options.output_dir, timing, options.plots);
}

}  // namespace pliant::cli
