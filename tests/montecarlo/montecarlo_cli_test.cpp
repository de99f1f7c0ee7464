// `pliant montecarlo` end to end: the same summary, byte for byte, on one
// thread, two threads and two MPI ranks; a killed study resumes to the same
// summary; a bad study file exits 2 naming the key.
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include <gtest/gtest.h>

#include "run_command.h"

namespace pliant {
namespace {

namespace fs = std::filesystem;

// Short pushes (0.2 s hold): about 0.02 s of work per trial.
fs::path WriteStudy(const fs::path& dir, int trials, const std::string& bad_key = "") {
  const fs::path path = dir / "study.json";
  std::ofstream(path) << R"({
  "format": "pliant-study", "version": 1, "description": "a short test study",
  "scenario": ")" PLIANT_SOURCE_DIR R"(/experiments/scenarios/divot.json",
  "scenario_set": ["hidden_effects={}", "experiment.hold_s=0.2", "experiment.rest_s=0.1"],
  "trials": )" << trials << R"(, "seed": 17,
  "instrument": {"compliance_scale": {"lognormal": [1.0, 0.1]}, "backlash_rad": {"uniform": [0.006, 0.01]}},
  "noise": {"effort_sd_nm": {"uniform": [0.005, 0.02]}},
  "contact": {"depth_m": {"uniform": [0.1, 0.2]}, "direction_deg": {"uniform": [0, 360]},
              "peak_torque_nm": {"uniform": [0.3, 1.0]}, "speed_rad_s": 0.05)"
                       << bad_key << R"(}
}
)";
  return path;
}

std::string Montecarlo(const fs::path& study, const fs::path& out, const std::string& extra) {
  return std::string(PLIANT_CLI) + " montecarlo '" + study.string() + "' -o '" + out.string() +
         "' --no-plots " + extra;
}

int DataRows(const fs::path& csv) {
  std::ifstream in(csv);
  int lines = 0;
  for (std::string line; std::getline(in, line);) ++lines;
  return lines - 2;  // the study line and the header
}

TEST(MontecarloCli, SameSummaryOnOneThreadTwoThreadsAndTwoMpiRanks) {
  const fs::path dir = testing::FreshDirectory("mc_split");
  const fs::path study = WriteStudy(dir, 24);
  const auto one = testing::RunCommand(Montecarlo(study, dir / "t1", "--threads 1"), dir);
  ASSERT_EQ(one.exit_code, 0) << one.err;
  const auto two = testing::RunCommand(Montecarlo(study, dir / "t2", "--threads 2"), dir);
  ASSERT_EQ(two.exit_code, 0) << two.err;
  EXPECT_EQ(one.err, "");  // no progress bar when stderr is not a terminal
  const std::string summary = testing::ReadText(dir / "t1" / "summary.json");
  EXPECT_NE(summary.find("\"trials\": 24"), std::string::npos);
  EXPECT_EQ(summary, testing::ReadText(dir / "t2" / "summary.json"));
  EXPECT_EQ(testing::ReadText(dir / "t1" / "trials.csv"), testing::ReadText(dir / "t2" / "trials.csv"));
#ifdef PLIANT_SANITIZE_BUILD
  GTEST_SKIP() << "2 MPI ranks: skipped in the sanitizer build (OpenMPI is not built with the "
                  "sanitizers and LSan reports its internals)";
#endif
  if (std::string(PLIANT_MPIRUN).empty()) GTEST_SKIP() << "mpirun not found at configure time";
  // As root (CI containers) mpirun needs --allow-run-as-root; --oversubscribe
  // lets 2 ranks start on a machine with fewer free slots. Both are harmless otherwise.
  const auto mpi = testing::RunCommand(std::string(PLIANT_MPIRUN) +
                                           " --allow-run-as-root --oversubscribe -n 2 " +
                                           Montecarlo(study, dir / "mpi", ""),
                                       dir);
  ASSERT_EQ(mpi.exit_code, 0) << mpi.err;
  EXPECT_NE(mpi.out.find("2 rank(s)"), std::string::npos) << mpi.out;
  EXPECT_EQ(summary, testing::ReadText(dir / "mpi" / "summary.json"));
  EXPECT_EQ(testing::ReadText(dir / "t1" / "trials.csv"), testing::ReadText(dir / "mpi" / "trials.csv"));
}

TEST(MontecarloCli, AKilledStudyResumesToTheSameSummary) {
  const fs::path dir = testing::FreshDirectory("mc_kill");
  const fs::path study = WriteStudy(dir, 40);
  const auto whole = testing::RunCommand(Montecarlo(study, dir / "whole", "--threads 2"), dir);
  ASSERT_EQ(whole.exit_code, 0) << whole.err;

  const fs::path out = dir / "killed";
  const std::string study_path = study.string(), out_path = out.string();
  const pid_t child = testing::StartPliantSilently(
      {"montecarlo", study_path, "-o", out_path, "--no-plots", "--threads", "1"});
  ASSERT_GE(child, 0);
  // SIGKILL once some trials are in: no destructor, no flush, maybe a torn row.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (DataRows(out / "trials.csv") < 8 && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  const int status = testing::KillAndReap(child);
  ASSERT_TRUE(WIFSIGNALED(status)) << "the study finished before the kill";
  ASSERT_FALSE(fs::exists(out / "summary.json"));
  const int done = DataRows(out / "trials.csv");
  ASSERT_GE(done, 8);
  ASSERT_LT(done, 40);

  const auto resumed = testing::RunCommand(Montecarlo(study, out, "--threads 2"), dir);
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  const std::string timing = testing::ReadText(out / "timing.json");
  // It redid none of the finished trials (a torn last row, if any, runs again).
  const int run = std::stoi(timing.substr(timing.find("\"trials_run\": ") + 14));
  EXPECT_LE(run, 40 - done + 1);
  EXPECT_GE(run, 40 - done);
  EXPECT_EQ(testing::ReadText(out / "summary.json"), testing::ReadText(dir / "whole" / "summary.json"));
  EXPECT_EQ(testing::ReadText(out / "trials.csv"), testing::ReadText(dir / "whole" / "trials.csv"));
}

TEST(MontecarloCli, ABadStudyExits2NamingTheKey) {
  const fs::path dir = testing::FreshDirectory("mc_bad");
  const fs::path study = WriteStudy(dir, 5, R"(, "force_n": 3)");
  const auto r = testing::RunCommand(Montecarlo(study, dir / "out", ""), dir);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("study.json:9:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("'force_n' in contact"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "out"));
}

TEST(MontecarloCli, RefusesToMixTwoStudiesInOneDirectory) {
  const fs::path dir = testing::FreshDirectory("mc_mix");
  const auto first = testing::RunCommand(Montecarlo(WriteStudy(dir, 3), dir / "out", ""), dir);
  ASSERT_EQ(first.exit_code, 0) << first.err;
  std::string text = testing::ReadText(dir / "study.json");
  text.replace(text.find("\"seed\": 17"), 10, "\"seed\": 18");
  std::ofstream(dir / "study.json") << text;
  const auto second = testing::RunCommand(Montecarlo(dir / "study.json", dir / "out", ""), dir);
  EXPECT_EQ(second.exit_code, 2);
  EXPECT_NE(second.err.find("trials.csv:1:"), std::string::npos) << second.err;
  EXPECT_NE(second.err.find("another study"), std::string::npos) << second.err;
}

}  // namespace
}  // namespace pliant
