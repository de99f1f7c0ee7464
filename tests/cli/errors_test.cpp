// Every message of docs/errors.md that no other test checks, as a user meets it:
// the exit status, the exact text on stderr, and no output file left behind.
#include <string>

#include <gtest/gtest.h>

#include "errors_test_support.h"

namespace pliant {
namespace {

using namespace errors_test;

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

}  // namespace
}  // namespace pliant
