// Every message of docs/errors.md that no other test checks, as a user meets it:
// the exit status, the exact text on stderr, and no output file left behind.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "clamped_beam_log.h"
#include "paper_parameters.h"
#include "pliant/io/log_writer.h"
#include "run_command.h"

namespace pliant {
namespace {

namespace fs = std::filesystem;
using testing::CommandResult;
using testing::FreshDirectory;
using testing::ReadText;
using testing::RunCommand;

const std::string kCli = PLIANT_CLI;
const std::string kSource = PLIANT_SOURCE_DIR;
const std::string kParams = kSource + "/data/paper.json";
const std::string kGoodLog = "t,q1,q2,q3,tau1,tau2\n0,0,0,0.1,0,0\n0.01,0,0,0.1,0.1,0\n";

void WriteText(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

std::string Quoted(const fs::path& path) { return "'" + path.string() + "'"; }

// Neither the output nor a temporary of it exists in `dir`.
void ExpectNothingWritten(const fs::path& dir, const std::string& output) {
  EXPECT_FALSE(fs::exists(dir / output)) << output << " was written";
  for (const auto& entry : fs::directory_iterator(dir)) {
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos)
        << "temporary file left: " << entry.path();
  }
}

// ---------------------------------------------------------------- log files

struct BadLogCase {
  const char* name;
  const char* content;
  const char* flags;
  const char* message;  // what follows "<path>" on stderr
};

void PrintTo(const BadLogCase& c, std::ostream* os) { *os << c.name; }

class LogError : public ::testing::TestWithParam<BadLogCase> {};

TEST_P(LogError, ExitsTwoWithTheExactMessageAndWritesNothing) {
  const BadLogCase c = GetParam();
  const auto dir = FreshDirectory(std::string("errors_log_") + c.name);
  const fs::path input = dir / "in.csv";
  WriteText(input, c.content);
  const auto r = RunCommand(kCli + " correct --params " + kParams + " " + c.flags + " " +
                                Quoted(input) + " -o " + Quoted(dir / "out.csv"),
                            dir);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(r.err, input.string() + c.message + "\n");
  EXPECT_EQ(r.out, "");
  ExpectNothingWritten(dir, "out.csv");
}

INSTANTIATE_TEST_SUITE_P(
    NotCheckedAtTheCommandLineElsewhere, LogError,
    ::testing::Values(
        BadLogCase{"metadata_only", "# robot: PSM1\n# date: today\n", "",
                   ":2: the file has metadata lines but no header row \u2014 add a header row "
                   "naming the columns (t,q1,q2,q3,tau1,tau2 at least) after the metadata"},
        BadLogCase{"unnamed_column", "t,q1,q2,q3,tau1,tau2,\n0,0,0,0.1,0,0,\n", "",
                   ":1:7: column 7 of the header has no name \u2014 name every column, and "
                   "remove any trailing comma from the header row"},
        BadLogCase{"number_too_large", "t,q1,q2,q3,tau1,tau2,temp\n0,0,0,0.1,0,0,1e400\n", "",
                   ":2:7: value '1e400' in column 'temp' is out of the range of a double \u2014 "
                   "check the value; magnitudes must lie between about 1e-308 and 1e308 (or be "
                   "0)"},
        BadLogCase{"inf_in_other_column", "t,q1,q2,q3,tau1,tau2,v1\n0,0,0,0.1,0,0,inf\n", "",
                   ":2:7: column 'v1' holds 'inf' \u2014 write finite values; leave the field "
                   "empty when the value is missing"},
        BadLogCase{"empty_required", "t,q1,q2,q3,tau1,tau2\n0,0,0,0.1,,0\n", "",
                   ":2:5: required column 'tau1' holds no value \u2014 give every row a finite t, "
                   "q1, q2, q3, tau1 and tau2, or pass --skip-bad-rows (option skip_bad_rows) to "
                   "drop and count such rows"},
        BadLogCase{"negative_depth", "t,q1,q2,q3,tau1,tau2\n0,0,0,-0.01,0,0\n", "",
                   ":2:4: q3 = -0.01 m is outside 0\u20130.3 m \u2014 q3 is the insertion depth "
                   "in metres and cannot be negative; check the joint 3 sign and offset"},
        BadLogCase{"every_row_skipped", "t,q1,q2,q3,tau1,tau2\n0,0,0,0.1,,0\n1,nan,0,0.1,0,0\n",
                   "--skip-bad-rows",
                   ":3: no usable data rows: all 2 rows were skipped as bad \u2014 give the rows "
                   "finite values in t, q1, q2, q3, tau1 and tau2"}),
    [](const auto& info) { return std::string(info.param.name); });

TEST(LogError, ADirectoryCannotBeRead) {
  const auto dir = FreshDirectory("errors_log_directory");
  fs::create_directories(dir / "run");
  const auto r = RunCommand(kCli + " correct --params " + kParams + " " + Quoted(dir / "run") +
                                " -o " + Quoted(dir / "out.csv"),
                            dir);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(r.err, (dir / "run").string() +
                       ": cannot read the log (Is a directory) \u2014 check that the file is "
                       "readable and the disk is healthy\n");
  ExpectNothingWritten(dir, "out.csv");
}

// The same reader behind every command: the same message, and no output.
TEST(LogError, EveryCommandReportsABadLogTheSameWay) {
  const auto dir = FreshDirectory("errors_log_every_command");
  WriteText(dir / "in.csv", "t,q1,q2,q3,tau1,tau2\n0,0,0,120,0,0\n");
  const std::string expected = (dir / "in.csv").string() +
                               ":2:4: q3 = 120 m is outside 0\u20130.3 m \u2014 this looks like "
                               "millimetres; convert to metres (divide by 1000)\n";
  for (const std::string command :
       {"correct --params " + kParams, "filter --params " + kParams, std::string("identify")}) {
    const auto r = RunCommand(kCli + " " + command + " " + Quoted(dir / "in.csv") + " -o " +
                                  Quoted(dir / "out"),
                              dir);
    EXPECT_EQ(r.exit_code, 2) << command << ": " << r.err;
    EXPECT_EQ(r.err, expected) << command;
    ExpectNothingWritten(dir, "out");
  }
}

// --------------------------------------------------------- parameters files

struct BadParametersCase {
  const char* name;
  const char* from;     // text of data/paper.json (first occurrence) ...
  const char* to;       // ... replaced by this
  const char* message;  // what follows "<path>" on stderr
};

void PrintTo(const BadParametersCase& c, std::ostream* os) { *os << c.name; }

class ParametersError : public ::testing::TestWithParam<BadParametersCase> {};

TEST_P(ParametersError, ExitsTwoWithTheExactMessageAndWritesNothing) {
  const BadParametersCase c = GetParam();
  const auto dir = FreshDirectory(std::string("errors_params_") + c.name);
  std::string text = ReadText(kParams);
  const std::size_t at = text.find(c.from);
  ASSERT_NE(at, std::string::npos) << c.from;
  text.replace(at, std::string(c.from).size(), c.to);
  WriteText(dir / "p.json", text);
  WriteText(dir / "in.csv", kGoodLog);
  const auto r = RunCommand(kCli + " correct --params " + Quoted(dir / "p.json") + " " +
                                Quoted(dir / "in.csv") + " -o " + Quoted(dir / "out.csv"),
                            dir);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(r.err, (dir / "p.json").string() + c.message + "\n");
  ExpectNothingWritten(dir, "out.csv");
}

#define SEE_DOCS " (docs/parameters.md shows a complete file)"

INSTANTIATE_TEST_SUITE_P(
    NotCheckedElsewhere, ParametersError,
    ::testing::Values(
        BadParametersCase{"not_an_object",
                          "\"tau_min_nm\": {\n      \"value\": 0.1,\n      \"source\": \"paper "
                          "section 2, after eq. (2)\"\n    },",
                          "\"tau_min_nm\": 0.1,",
                          ":20:5: joint1.tau_min_nm must be an object, found number \u2014 write "
                          "it as { ... }" SEE_DOCS},
        BadParametersCase{"bias_form", "\"angle_rad\": [-1.588, 1.588],",
                          "\"form\": \"spline\", \"angle_rad\": [-1.588, 1.588],",
                          ":7:7: joint1.bias_torque.form is 'spline' \u2014 write \"table\" "
                          "(angle_rad, torque_nm) or \"fourier\" (coefficients a0, a1, b1, \u2026)"},
        BadParametersCase{"covariance_names", "  }\n}",
                          "  },\n  \"covariance\": {\"names\": \"joint1.backlash_rad\", "
                          "\"matrix\": []}\n}",
                          ":61:18: covariance.names must be an array of strings, found string "
                          "\u2014 write it as [\"joint1.backlash_rad\", ...]"},
        BadParametersCase{"table_lengths", "\"torque_nm\": [0.199, 0.199],",
                          "\"torque_nm\": [0.199],",
                          ":6:5: joint1: bias_torque needs as many angle_rad as torque_nm values, "
                          "at least one \u2014 correct the value" SEE_DOCS},
        BadParametersCase{"fourier_even", "\"angle_rad\": [-1.588, 1.588],\n      \"torque_nm\": "
                                          "[0.199, 0.199],",
                          "\"form\": \"fourier\", \"coefficients\": [0.1, 0.2],",
                          ":6:5: joint1: bias_torque coefficients must be a0, a1, b1, \u2026 (an "
                          "odd number, at least one) \u2014 correct the value" SEE_DOCS},
        BadParametersCase{"fourier_reference_depth",
                          "\"angle_rad\": [-1.588, 1.588],\n      \"torque_nm\": [0.199, 0.199],",
                          "\"form\": \"fourier\", \"coefficients\": [0.1], "
                          "\"reference_depth_m\": -1,",
                          ":6:5: joint1: bias_torque depth_slope_nm_per_m must be finite and "
                          "reference_depth_m >= 0 \u2014 correct the value" SEE_DOCS},
        BadParametersCase{"depth_range", "\"value\": [0.09, 0.22],", "\"value\": [0.22, 0.09],",
                          ":28:5: joint1: depth_range_m must be [min, max] with 0 < min < max <= "
                          "0.3 m \u2014 correct the value" SEE_DOCS},
        BadParametersCase{"tau_min", "\"value\": 0.1,", "\"value\": 12,",
                          ":20:5: joint1: tau_min_nm must be in [0, 10) N\u00b7m \u2014 correct "
                          "the value" SEE_DOCS}),
    [](const auto& info) { return std::string(info.param.name); });

// ------------------------------------------------ scenarios and --set

struct BadScenarioCase {
  const char* name;
  const char* scenario;  // experiments/scenarios/<scenario>.json
  const char* set;       // the --set override
  const char* message;   // what follows "--set <set>" on stderr
};

void PrintTo(const BadScenarioCase& c, std::ostream* os) { *os << c.name; }

class ScenarioError : public ::testing::TestWithParam<BadScenarioCase> {};

TEST_P(ScenarioError, ExitsTwoNamingTheOverrideAndWritesNothing) {
  const BadScenarioCase c = GetParam();
  const auto dir = FreshDirectory(std::string("errors_scenario_") + c.name);
  const auto r = RunCommand(kCli + " simulate " + kSource + "/experiments/scenarios/" +
                                c.scenario + ".json --set '" + c.set + "' -o " +
                                Quoted(dir / "out.csv"),
                            dir);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(r.err, std::string("--set ") + c.set + ": " + c.message + "\n");
  ExpectNothingWritten(dir, "out.csv");
}

INSTANTIATE_TEST_SUITE_P(
    NotCheckedElsewhere, ScenarioError,
    ::testing::Values(
        BadScenarioCase{"format", "clamped_beam", "format=x",
                        "format must be \"pliant-scenario\" \u2014 is this a scenario file?"},
        BadScenarioCase{"not_whole", "clamped_beam", "version=1.5",
                        "version must be a whole number, found 1.5 \u2014 write an integer"},
        BadScenarioCase{"not_a_string", "clamped_beam", "description=3",
                        "description must be a string, found 3 \u2014 write it in double quotes"},
        BadScenarioCase{"not_an_object", "clamped_beam", "truth=3",
                        "truth must be an object, found number \u2014 write it as { ... } "
                        "(docs/simulator.md shows every section)"},
        BadScenarioCase{"not_a_number", "clamped_beam", "experiment.tip_step_m=abc",
                        "experiment.tip_step_m must be a number, found string \u2014 write a "
                        "number in m"},
        BadScenarioCase{"empty_array", "clamped_beam", "experiment.depths_m=[]",
                        "experiment.depths_m must be a non-empty array, found [] \u2014 write it "
                        "as [numbers in m]"},
        BadScenarioCase{"array_size", "clamped_beam", "truth.backlash_rad=[0.1]",
                        "truth.backlash_rad must be 2 values, found [0.1] \u2014 write it as "
                        "[numbers in rad]"},
        BadScenarioCase{"experiment_not_object", "clamped_beam", "experiment=3",
                        "experiment must be an object with a \"type\" \u2014 write \"experiment\": "
                        "{\"type\": \"clamped_beam\", ...}"},
        BadScenarioCase{"experiment_type", "clamped_beam", "experiment.type=stretch",
                        "unknown experiment type 'stretch' \u2014 use one of bias_sweep, "
                        "clamped_beam, divot, free_motion"},
        BadScenarioCase{"range_order", "bias_sweep", "experiment.joint1_range_deg=[10,-10]",
                        "joint1_range_deg must be [lower, upper] \u2014 swap them"},
        BadScenarioCase{"compliance_form", "clamped_beam", "truth.compliance.form=wrong",
                        "unknown compliance form 'wrong' \u2014 use inverse_cubic (the paper's "
                        "1/K(L)) or direct_cubic (the dVRK file's K(L))"},
        BadScenarioCase{"tracker", "clamped_beam", "sensors.tracker=1",
                        "sensors.tracker must be true or false \u2014 write true or false"},
        BadScenarioCase{"hidden_effects_not_object", "clamped_beam", "hidden_effects=3",
                        "hidden_effects must be an object \u2014 write { \"name\": {...} }"},
        BadScenarioCase{"log_mode", "clamped_beam", "log.mode=everything",
                        "unknown log mode 'everything' \u2014 use all, holds or hold_means"}),
    [](const auto& info) { return std::string(info.param.name); });

TEST(ScenarioError, FileErrorsNameTheFileAndWriteNothing) {
  const auto dir = FreshDirectory("errors_scenario_files");
  const auto missing = RunCommand(kCli + " simulate " + Quoted(dir / "nope.json") + " -o " +
                                      Quoted(dir / "out.csv"),
                                  dir);
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_EQ(missing.err, (dir / "nope.json").string() +
                             ": cannot open the scenario file \u2014 check the path (scenarios "
                             "live in experiments/scenarios/)\n");
  WriteText(dir / "list.json", "[1, 2]\n");
  const auto list = RunCommand(kCli + " simulate " + Quoted(dir / "list.json") + " -o " +
                                   Quoted(dir / "out.csv"),
                               dir);
  EXPECT_EQ(list.exit_code, 2);
  EXPECT_EQ(list.err, (dir / "list.json").string() +
                          ":1:1: a scenario must be a JSON object \u2014 see docs/simulator.md\n");
  // An error in the file itself points at its line and column.
  std::string text = ReadText(kSource + "/experiments/scenarios/clamped_beam.json");
  const std::string from = "\"format\": \"pliant-scenario\"";
  ASSERT_NE(text.find(from), std::string::npos);
  text.replace(text.find(from), from.size(), "\"format\": \"pliant-parameters\"");
  WriteText(dir / "s.json", text);
  const auto located = RunCommand(kCli + " simulate " + Quoted(dir / "s.json") + " -o " +
                                      Quoted(dir / "out.csv"),
                                  dir);
  EXPECT_EQ(located.exit_code, 2);
  EXPECT_EQ(located.err, (dir / "s.json").string() +
                             ":2:3: format must be \"pliant-scenario\" \u2014 is this a scenario "
                             "file?\n");
  ExpectNothingWritten(dir, "out.csv");
}

// ---------------------------------------------------------- filter options

struct FilterOptionCase {
  const char* name;
  const char* option;
  const char* message;
};

void PrintTo(const FilterOptionCase& c, std::ostream* os) { *os << c.name; }

class FilterOptionError : public ::testing::TestWithParam<FilterOptionCase> {};

TEST_P(FilterOptionError, ExitsTwoNamingTheOptionAndWritesNothing) {
  const FilterOptionCase c = GetParam();
  const auto dir = FreshDirectory(std::string("errors_filter_") + c.name);
  WriteText(dir / "in.csv", kGoodLog);
  const auto r = RunCommand(kCli + " filter --params " + kParams + " " + c.option + " " +
                                Quoted(dir / "in.csv") + " -o " + Quoted(dir / "out.csv"),
                            dir);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(r.err, std::string(c.message) + "\n");
  ExpectNothingWritten(dir, "out.csv");
}

INSTANTIATE_TEST_SUITE_P(
    EveryOption, FilterOptionError,
    ::testing::Values(
        FilterOptionCase{"effort_noise", "--effort-noise 0",
                         "--effort-noise: effort_noise_nm = 0.000000 must be finite and > 0 "
                         "\u2014 give it in N\u00b7m"},
        FilterOptionCase{"encoder_noise", "--encoder-noise -1",
                         "--encoder-noise: encoder_noise_rad = -1.000000 must be finite and > 0 "
                         "\u2014 give it in rad"},
        FilterOptionCase{"torque_rate", "--torque-rate nan",
                         "--torque-rate: external_torque_rate_nm = nan must be finite and > 0 "
                         "\u2014 give it in N\u00b7m/\u221as"},
        FilterOptionCase{"compliance_sd", "--compliance-sd 0",
                         "--compliance-sd: compliance_scale_sd = 0.000000 must be finite and > 0 "
                         "\u2014 give it in (a fraction of K)"},
        FilterOptionCase{"gate", "--gate 1.5",
                         "--gate: gate_probability = 1.500000 must lie in (0.5, 1) \u2014 it is "
                         "the probability that a measurement the model explains passes, e.g. "
                         "0.9999 or 0.99"},
        FilterOptionCase{"mismatch_window", "--mismatch-window 3",
                         "--mismatch-window: mismatch_window must be in [10, 100000] samples "
                         "\u2014 e.g. 300 (0.2 s at 1.5 kHz)"}),
    [](const auto& info) { return std::string(info.param.name); });

// ------------------------------------------------------------ command line

struct UsageCase {
  const char* name;
  std::string arguments;
  const char* message;  // the first line on stderr
};

void PrintTo(const UsageCase& c, std::ostream* os) { *os << c.name; }

class UsageError : public ::testing::TestWithParam<UsageCase> {};

TEST_P(UsageError, ExitsTwoWithCli11sMessageAndWritesNothing) {
  const UsageCase c = GetParam();
  const auto dir = FreshDirectory(std::string("errors_usage_") + c.name);
  WriteText(dir / "in.csv", kGoodLog);
  const auto r = RunCommand("cd " + Quoted(dir) + " && " + kCli + " " + c.arguments, dir);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(r.err, std::string(c.message) + "\nRun with --help for more information.\n");
  ExpectNothingWritten(dir, "out.csv");
}

INSTANTIATE_TEST_SUITE_P(
    Cli11, UsageError,
    ::testing::Values(
        UsageCase{"no_subcommand", "", "A subcommand is required"},
        UsageCase{"missing_option", "correct in.csv -o out.csv", "--params is required"},
        UsageCase{"missing_output", ("correct --params " + kParams + " in.csv"),
                  "--output is required"},
        UsageCase{"bad_model",
                  ("correct --params " + kParams + " --model magic in.csv -o out.csv"),
                  "--model: magic not in {paper,deadzone}"},
        UsageCase{"bad_method", "identify --method magic in.csv -o out.csv",
                  "--method: magic not in {auto,paper,smoother,quasi_static}"},
        UsageCase{"out_of_range", "identify --harmonics 9 in.csv -o out.csv",
                  "--harmonics: Value 9 not in range 0 to 6"},
        UsageCase{"not_a_number", ("params " + kParams + " --depth abc"),
                  "Could not convert: --depth = abc"},
        UsageCase{"extra_argument",
                  ("correct --params " + kParams + " in.csv extra.csv -o out.csv"),
                  "The following argument was not expected: extra.csv"}),
    [](const auto& info) { return std::string(info.param.name); });

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

fs::path WriteCalibration(const fs::path& dir, pliant::testing::CalibrationLogSpec spec) {
  spec.truth = models::testing::PaperParameters();
  const fs::path path = dir / "calibration.csv";
  io::WriteLog(path.string(), pliant::testing::MakeCalibrationLog(spec));
  return path;
}

TEST(Warning, IdentifyWithoutABiasSweepSaysTheBiasKeepsItsPrior) {
  const auto dir = FreshDirectory("errors_warning_no_sweep");
  pliant::testing::CalibrationLogSpec spec;
  spec.depths_m = {0.10, 0.14, 0.18, 0.22};
  spec.bias_sweep = false;
  const auto log = WriteCalibration(dir, spec);
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
  const auto log = WriteCalibration(dir, spec);
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
