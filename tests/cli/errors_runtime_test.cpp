// docs/errors-runtime.md's runtime failures, destination checks, warnings and the
// unknown command, as a user meets them (the input errors: errors_test.cpp).
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "clamped_beam_log.h"
#include "errors_test_support.h"
#include "paper_parameters.h"
#include "pliant/io/log_writer.h"

namespace pliant {
namespace {

using namespace errors_test;

// ----------------------------------------------------------- runtime (exit 1)

// The destination is checked before any work: a missing directory or an
// output that is a directory is bad usage (exit 2), said before a single row is read.
TEST(OutputError, AMissingOutputDirectoryExitsTwoBeforeAnyWork) {
  const auto dir = FreshDirectory("errors_runtime_directory");
  WriteText(dir / "in.csv", kGoodLog);
  const fs::path output = dir / "no" / "such" / "out.csv";
  const auto r = RunCommand(kCli + " correct --params " + kParams + " " + Quoted(dir / "in.csv") +
                                " -o " + Quoted(output),
                            dir);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  const std::string missing = (dir / "no" / "such").string();
  EXPECT_EQ(r.err, "-o " + output.string() + ": the directory " + missing +
                       " does not exist \u2014 create it first (mkdir -p " + missing +
                       ") or write elsewhere\n");
  EXPECT_FALSE(fs::exists(dir / "no"));
}

TEST(OutputError, AnOutputThatIsADirectoryExitsTwoAndLeavesItAlone) {
  const auto dir = FreshDirectory("errors_runtime_replace");
  WriteText(dir / "in.csv", kGoodLog);
  fs::create_directories(dir / "out.csv");
  const auto r = RunCommand(kCli + " correct --params " + kParams + " " + Quoted(dir / "in.csv") +
                                " -o " + Quoted(dir / "out.csv"),
                            dir);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  const std::string out = (dir / "out.csv").string();
  EXPECT_EQ(r.err, "-o " + out + ": is a directory \u2014 give a file name (e.g. " + out +
                       "/out)\n");
  EXPECT_TRUE(fs::is_directory(dir / "out.csv"));
  EXPECT_TRUE(fs::is_empty(dir / "out.csv"));
}

// The figure is drawn after the output is complete: a figure failure exits 1
// and keeps the (whole) output, but draws no picture.
TEST(RuntimeError, FigureFailuresExitOneAndDrawNothing) {
  const auto dir = FreshDirectory("errors_runtime_figure");
  WriteText(dir / "in.csv", kGoodLog);
  const std::string identify = "cd " + Quoted(dir) + " && ";
  const std::string args = " identify --method paper in.csv -o p.json --figure ";
  const auto jpg = RunCommand(identify + kCli + args + "f.jpg", dir);
  EXPECT_EQ(jpg.exit_code, 1) << jpg.err;
  EXPECT_NE(jpg.err.find("pliant: figure " + (dir / "f.jpg").string() +
                         ": use a .png or .svg file name\n"),
            std::string::npos)
      << jpg.err;
  const auto none =
      RunCommand(identify + "PLIANT_GNUPLOT=/nonexistent/gnuplot " + kCli + args + "f.png", dir);
  EXPECT_EQ(none.exit_code, 1) << none.err;
  EXPECT_NE(none.err.find("pliant: cannot draw f.png: gnuplot was not found on the PATH \u2014 "
                          "install it (Debian: apt-get install gnuplot-nox) or set "
                          "PLIANT_GNUPLOT to its path\n"),
            std::string::npos)
      << none.err;
  const auto failing = RunCommand(identify + "PLIANT_GNUPLOT=/bin/false " + kCli + args + "f.png", dir);
  EXPECT_EQ(failing.exit_code, 1) << failing.err;
  EXPECT_NE(failing.err.find("pliant: gnuplot failed to draw f.png: "), std::string::npos)
      << failing.err;
  EXPECT_FALSE(fs::exists(dir / "f.png"));
  EXPECT_FALSE(fs::exists(dir / "f.jpg"));
  EXPECT_NE(ReadText(dir / "p.json").find("\"format\": \"pliant-parameters\""), std::string::npos);
}

// ---------------------------------------------------------------- warnings

TEST(Warning, ParamsOutsideTheValidRangeSaysKIsTheNearestEnds) {
  const auto dir = FreshDirectory("errors_warning_params");
  const auto r = RunCommand(kCli + " params " + kParams + " --depth 0.25", dir);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("  warning: the depth is outside the parameters' valid range; K is the "
                       "nearest end's\n"),
            std::string::npos)
      << r.out;
}

TEST(Warning, FilterCountsRowsOutsideTheValidRange) {
  const auto dir = FreshDirectory("errors_warning_filter");
  WriteText(dir / "in.csv", "t,q1,q2,q3,tau1,tau2\n0,0,0,0.1,0,0\n0.01,0,0,0.3,0,0\n");
  const auto r = RunCommand(kCli + " filter --params " + kParams + " " + Quoted(dir / "in.csv") +
                                " -o " + Quoted(dir / "out.csv"),
                            dir);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "warning: 1 rows have an insertion depth outside the parameters' valid "
                   "range; K(L) used the nearest valid depth for them\n");
  EXPECT_TRUE(fs::exists(dir / "out.csv"));
}

TEST(Warning, IdentifyWithoutABiasSweepSaysTheBiasKeepsItsPrior) {
  const auto dir = FreshDirectory("errors_warning_no_sweep");
  pliant::testing::CalibrationLogSpec spec;
  spec.depths_m = {0.10, 0.14, 0.18, 0.22};
  spec.bias_sweep = false;
  const auto log = pliant::testing::WritePaperCalibrationLog(dir, spec);
  // The smoother (the paper's procedure refuses held-tip logs alone).
  const auto r = RunCommand(kCli + " identify " + Quoted(log) + " -o " +
                                Quoted(dir / "p.json"),
                            dir);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("warning: no free-tip samples (no bias sweep): the bias torque tau0(q) is "
                       "not measured (a held tip cannot tell its slope from 1/K, nor its level "
                       "from the tip angle); it keeps its prior — record a bias sweep (the "
                       "paper's Fig. 4 protocol) to measure it\n"),
            std::string::npos)
      << r.err;
}

TEST(Warning, IdentifyWithATipNeverLoadedSaysKAndDeltaKeepTheirPrior) {
  const auto dir = FreshDirectory("errors_warning_unloaded");
  pliant::testing::CalibrationLogSpec spec;
  spec.depths_m = {0.12, 0.18};
  spec.torque_limit_nm = 0.05;  // below the contact thresholds (0.1, 0.2 N·m)
  const auto log = pliant::testing::WritePaperCalibrationLog(dir, spec);
  const auto r = RunCommand(kCli + " identify --method paper " + Quoted(log) + " -o " +
                                Quoted(dir / "p.json"),
                            dir);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("warning: joint 1: the held tip is never loaded beyond 0.10 N\u00b7m: "
                       "K1(L) and delta1 cannot be identified; they keep their prior\n"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("warning: joint 2: the held tip is never loaded beyond 0.20 N\u00b7m"),
            std::string::npos)
      << r.err;
}

TEST(UsageError, AnUnknownCommandIsNamedWithTheKnownOnes) {
  const auto dir = FreshDirectory("errors_unknown_command");
  const auto r = RunCommand(kCli + " identfy in.csv", dir);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err,
            "pliant: unknown command 'identfy' \u2014 use one of: correct, identify, params, "
            "simulate, filter, diagnose, montecarlo, import (pliant --help)\n");
}


}  // namespace
}  // namespace pliant
