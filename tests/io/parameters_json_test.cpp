#include "pliant/io/parameters_json.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <regex>

#include "pliant/io/input_error.h"
#include "pliant/models/paper_parameters.h"
#include "temp_directory.h"

namespace pliant::io {
namespace {

using models::ComplianceForm;
using testing::ReadText;
using testing::TempDirectory;

const std::string kPaperPath = std::string(PLIANT_SOURCE_DIR) + "/data/paper.json";
const std::string kSeeDocs = " (docs/parameters.md shows a complete file)";

// paper.json with `from` replaced by `to` (which must occur exactly once).
std::string PaperWith(const std::string& from, const std::string& to) {
  std::string text = ReadText(kPaperPath);
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  EXPECT_EQ(text.find(from, at + 1), std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

std::string ErrorOf(const std::string& text) {
  try {
    ParseParameters(text, "p.json");
  } catch (const InputError& error) {
    return error.what();
  }
  return "no error";
}

// Line (from 1) of the first occurrence of `needle`: an independent check of
// the locator's answer.
std::size_t LineOf(const std::string& text, const std::string& needle) {
  const std::size_t at = text.find(needle);
  return 1 + static_cast<std::size_t>(std::count(text.begin(), text.begin() + at, '\n'));
}

void ExpectEqual(const models::ModelParameters& a, const models::ModelParameters& b) {
  EXPECT_EQ(a.description, b.description);
  for (int j = 0; j < 2; ++j) {
    const auto &x = a.joints[j], &y = b.joints[j];
    EXPECT_EQ(x.bias_torque.angle_rad, y.bias_torque.angle_rad);
    EXPECT_EQ(x.bias_torque.torque_nm, y.bias_torque.torque_nm);
    EXPECT_EQ(x.compliance.form, y.compliance.form);
    EXPECT_EQ(x.compliance.cubic.coefficients, y.compliance.cubic.coefficients);
    EXPECT_EQ(x.backlash_rad, y.backlash_rad);
    EXPECT_EQ(x.tau_min_nm, y.tau_min_nm);
    EXPECT_EQ(x.deadzone_width_nm, y.deadzone_width_nm);
    EXPECT_EQ(x.depth_min_m, y.depth_min_m);
    EXPECT_EQ(x.depth_max_m, y.depth_max_m);
    EXPECT_EQ(x.sources, y.sources);
    EXPECT_EQ(x.bias_form, y.bias_form);
    EXPECT_EQ(x.bias_fourier.coefficients, y.bias_fourier.coefficients);
    EXPECT_EQ(x.bias_fourier.depth_slope_nm_per_m, y.bias_fourier.depth_slope_nm_per_m);
    EXPECT_EQ(x.bias_fourier.reference_depth_m, y.bias_fourier.reference_depth_m);
    EXPECT_EQ(x.bias_fourier.depth_harmonic_nm_per_m, y.bias_fourier.depth_harmonic_nm_per_m);
  }
  ASSERT_EQ(a.covariance.has_value(), b.covariance.has_value());
  if (a.covariance) {
    EXPECT_EQ(a.covariance->names, b.covariance->names);
    EXPECT_TRUE(a.covariance->matrix == b.covariance->matrix);
  }
}

TEST(ParametersJson, ReadsThePapersModel) {
  const models::ModelParameters p = ReadParameters(kPaperPath);
  const auto& j1 = p.joints[0];
  const auto& j2 = p.joints[1];
  EXPECT_EQ(j1.compliance.form, ComplianceForm::kInverseCubic);
  EXPECT_EQ(j1.compliance.cubic.coefficients,
            (std::array<double, 4>{639.16, -432.35, 136.32, 3.12}));
  EXPECT_EQ(j2.compliance.cubic.coefficients,
            (std::array<double, 4>{3163.17, -1969.15, 448.92, -6.0}));
  EXPECT_EQ(j1.tau_min_nm, 0.1);
  EXPECT_EQ(j2.tau_min_nm, 0.2);
  EXPECT_EQ(j1.deadzone_width_nm, 0.1);
  EXPECT_EQ(j2.deadzone_width_nm, 0.2);
  EXPECT_EQ(j1.backlash_rad, 0.008478);
  EXPECT_EQ(j2.backlash_rad, 0.007176);
  EXPECT_EQ(j1.depth_min_m, 0.09);
  EXPECT_EQ(j2.depth_max_m, 0.22);
  EXPECT_EQ(j1.bias_torque.angle_rad, (std::vector<double>{-1.588, 1.588}));
  EXPECT_EQ(j1.bias_torque.torque_nm, (std::vector<double>{0.199, 0.199}));
  EXPECT_EQ(j2.bias_torque.angle_rad, (std::vector<double>{-0.925, 0.925}));
  EXPECT_NEAR(j2.bias_torque.torque_nm[0], -0.2419 * 0.155 + 0.03458, 1e-15);
  EXPECT_EQ(j1.sources.at("compliance"), "paper eq. (3)");
  EXPECT_EQ(j2.sources.at("compliance"), "paper eq. (4)");
  EXPECT_EQ(j2.sources.at("tau_min_nm"), "paper section 2, after eq. (2)");
  EXPECT_EQ(j1.sources.size(), 6u);
  EXPECT_FALSE(p.covariance.has_value());
  // Paper eq. (3) at L = 0.15 m: 1/K1 = 2.157165 - 9.727875 + 20.448 + 3.12 N·m/rad.
  EXPECT_NEAR(1.0 / models::ComplianceAt(j1, 0.15), 15.99729, 1e-9);
}

TEST(ParametersJson, RoundTripIsIdentical) {
  TempDirectory directory;
  models::ModelParameters p = ReadParameters(kPaperPath);
  p.joints[1].compliance.form = ComplianceForm::kDirectCubic;
  p.joints[1].compliance.cubic.coefficients = {-16.1879, 9.1018, -1.7220, 0.1343};
  p.joints[0].sources.erase("backlash_rad");
  p.joints[0].bias_torque = {{-1.5, -0.1, 0.2, 1.5}, {0.1 / 3, 1e-300, -0.0, 0.3}};
  models::ParameterCovariance covariance;
  covariance.names = {"joint1.backlash_rad", "joint2.backlash_rad", "joint1.compliance.c0"};
  covariance.matrix.resize(3, 3);
  covariance.matrix << 1e-6, 2e-8, 0.0, 2e-8, 4e-6, 1.0 / 3e7, 0.0, 1.0 / 3e7, 0.01;
  p.covariance = covariance;
  const std::string path = directory.File("out.json");
  WriteParameters(path, p);
  ExpectEqual(p, ReadParameters(path));
  ExpectEqual(p, ParseParameters(ParametersToJson(p).dump(), "mem"));
  WriteParameters(directory.File("again.json"), ReadParameters(path));
  EXPECT_EQ(ReadText(directory.File("again.json")), ReadText(path));
  // Written in the documented key order, not alphabetically.
  EXPECT_LT(ReadText(path).find("\"format\""), ReadText(path).find("\"description\""));
}

TEST(ParametersJson, BeamSeriesLawAndFourierBiasRoundTrip) {
  TempDirectory directory;
  models::ModelParameters p = ReadParameters(kPaperPath);
  p.joints[0].compliance = {ComplianceForm::kBeamSeries, {{0.031, 0.0043, 0.0, 0.025}}};
  p.joints[1].bias_form = models::BiasForm::kFourier;
  p.joints[1].bias_fourier = {{0.03, -0.01, 0.12, 0.027, 0.0001}, -0.2405, 0.155, {0.21, -0.47}};
  p.joints[1].bias_torque = {};  // a Fourier bias has no table
  const std::string path = directory.File("identified.json");
  WriteParameters(path, p);
  const std::string text = ReadText(path);
  EXPECT_NE(text.find("\"depth_harmonic_nm_per_m\": [\n        0.21,\n        -0.47"),
            std::string::npos) << text;
  EXPECT_NE(text.find("\"form\": \"beam_series\""), std::string::npos) << text;
  EXPECT_NE(text.find("\"structure_compliance_rad_per_n\": 0.0043"), std::string::npos) << text;
  EXPECT_NE(text.find("\"form\": \"fourier\""), std::string::npos) << text;
  ExpectEqual(p, ReadParameters(path));
}

// A Fourier bias written before the depth harmonic existed: no
// depth_harmonic_nm_per_m key. It reads as zero, and a file whose harmonic is
// zero is written without the key, so that such older readers accept it.
TEST(ParametersJson, AFourierBiasWithoutTheDepthHarmonicReadsItAsZero) {
  const std::string table = "\"angle_rad\": [-1.588, 1.588],\n      \"torque_nm\": [0.199, 0.199],";
  const std::string old_bias =
      "\"form\": \"fourier\", \"coefficients\": [0.03, -0.01, 0.12], "
      "\"depth_slope_nm_per_m\": -0.2405, \"reference_depth_m\": 0.155,";
  const models::ModelParameters p = ParseParameters(
      PaperWith(table, old_bias),
      "old.json");
  const auto& f = p.joints[0].bias_fourier;
  ASSERT_EQ(p.joints[0].bias_form, models::BiasForm::kFourier);
  EXPECT_EQ(f.depth_harmonic_nm_per_m, (std::array<double, 2>{0.0, 0.0}));
  EXPECT_EQ(f.depth_slope_nm_per_m, -0.2405);
  // tau0 is the old file's: a0 + a1·cos q + b1·sin q + s·(L − L_ref).
  EXPECT_NEAR(models::BiasTorqueAt(p.joints[0], 0.4, 0.2),
              0.03 - 0.01 * std::cos(0.4) + 0.12 * std::sin(0.4) - 0.2405 * 0.045, 1e-15);
  TempDirectory directory;
  WriteParameters(directory.File("again.json"), p);
  EXPECT_EQ(ReadText(directory.File("again.json")).find("depth_harmonic"), std::string::npos);
  const std::string one_number =
      ErrorOf(PaperWith(table, old_bias + " \"depth_harmonic_nm_per_m\": [0.1],"));
  EXPECT_NE(one_number.find("depth_harmonic_nm_per_m must be an array of c1, d1 in N·m/m, found 1 "
                            "values"),
            std::string::npos)
      << one_number;
}

TEST(ParametersJson, BeamSeriesErrorsNameTheField) {
  const std::string beam =
      "\"form\": \"beam_series\",\n      \"joint_compliance_rad_per_nm\": 0.03,\n"
      "      \"structure_compliance_rad_per_n\": -0.004,\n      \"shaft_flexibility_per_nm2\": 0,\n"
      "      \"cannula_length_m\": 0.025";
  const std::string text =
      PaperWith("\"form\": \"inverse_cubic\",\n      \"coefficients\": [639.16, -432.35, 136.32, 3.12]", beam);
  EXPECT_EQ(ErrorOf(text),
            "p.json:11:5: joint1: compliance beam_series terms must be finite and >= 0 (each is a "
            "compliance or a length) \u2014 correct the value" + kSeeDocs);
}

TEST(ParametersJson, DeadzoneWidthDefaultsToTauMin) {
  const std::string text = PaperWith(
      "\"deadzone_width_nm\": {\n      \"value\": 0.2,\n      \"source\": \"pliant default: the "
      "dead-zone is taken up at the paper's tau_min\"\n    },\n",
      "");
  const auto p = ParseParameters(text, "p.json");
  EXPECT_EQ(p.joints[1].deadzone_width_nm, 0.2);
  EXPECT_EQ(p.joints[1].sources.count("deadzone_width_nm"), 0u);
}

TEST(ParametersJson, MissingFile) {
  try {
    ReadParameters("/nonexistent/p.json");
    FAIL() << "read a missing file";
  } catch (const InputError& error) {
    EXPECT_STREQ(error.what(),
                 "/nonexistent/p.json: cannot open the parameters file (No such file or "
                 "directory) \u2014 check the path; data/paper.json is a complete example");
  }
}

TEST(ParametersJson, UnknownKeysAreNamedWithTheAllowedOnes) {
  const std::string text = PaperWith("\"value\": 0.008478,", "\"value\": 0.008478, \"units\": 1,");
  EXPECT_EQ(ErrorOf(text),
            "p.json:17:26: unknown key 'units' in joint1.backlash_rad; allowed keys: "
            "value, source \u2014 remove the key or correct its spelling");
  EXPECT_EQ(ErrorOf("\xEF\xBB\xBF" + text), ErrorOf(text));  // a byte-order mark moves nothing
  const std::string joint = PaperWith("\"backlash_rad\": {\n      \"value\": 0.007176",
                                      "\"backlash\": {\n      \"value\": 0.007176");
  EXPECT_EQ(ErrorOf(joint), "p.json:" + std::to_string(LineOf(joint, "\"backlash\"")) +
                                ":5: unknown key 'backlash' in joint2; allowed keys: bias_torque, "
                                "compliance, backlash_rad, tau_min_nm, deadzone_width_nm, "
                                "depth_range_m \u2014 remove the key or correct its spelling");
  const std::string top = PaperWith("\"version\": 1,", "\"version\": 1,\n  \"Joint1\": {},");
  EXPECT_EQ(ErrorOf(top),
            "p.json:4:3: unknown key 'Joint1' in the top-level object; allowed "
            "keys: format, version, description, identified_from, joint1, joint2, covariance, "
            "effects \u2014 remove the key or correct its spelling");
}

TEST(ParametersJson, MissingRequiredKey) {
  const std::string text = PaperWith("\"format\": \"pliant-parameters\",\n", "");
  EXPECT_EQ(ErrorOf(text),
            "p.json:1:1: the top-level object has no key 'format' \u2014 add "
            "\"format\"" +
                kSeeDocs);
  const std::string joint = PaperWith("\"tau_min_nm\": {\n      \"value\": 0.2,", "\"x\": {");
  const std::string prefix =
      "p.json:" + std::to_string(LineOf(joint, "\"x\"")) + ":5: unknown key 'x' in joint2";
  EXPECT_EQ(ErrorOf(joint).substr(0, prefix.size()), prefix);
  const std::string no_tau = PaperWith(
      "\"tau_min_nm\": {\n      \"value\": 0.2,\n      \"source\": \"paper section 2, after eq. "
      "(2)\"\n    },\n    \"deadzone_width_nm\": {\n      \"value\": 0.2",
      "\"deadzone_width_nm\": {\n      \"value\": 0.2");
  EXPECT_EQ(ErrorOf(no_tau), "p.json:" + std::to_string(LineOf(no_tau, "\"joint2\"")) +
                                 ":3: joint2 has no key 'tau_min_nm' \u2014 add \"tau_min_nm\"" +
                                 kSeeDocs);
}

TEST(ParametersJson, WrongTypesAndShapes) {
  EXPECT_EQ(ErrorOf(PaperWith("\"value\": 0.008478", "\"value\": \"0.008478\"")),
            "p.json:17:7: joint1.backlash_rad.value must be a number, found string \u2014 write a "
            "number in rad");
  EXPECT_EQ(ErrorOf(PaperWith("[639.16, -432.35, 136.32, 3.12]", "[639.16, -432.35, 136.32]")),
            "p.json:13:7: joint1.compliance.coefficients must be an array of 4 numbers c3, c2, c1, "
            "c0, found 3 values \u2014 write it as [4 numbers c3, c2, c1, c0]");
  EXPECT_EQ(ErrorOf(PaperWith("[639.16, -432.35, 136.32, 3.12]", "[639.16, -432.35, null, 3.12]")),
            "p.json:13:41: joint1.compliance.coefficients.2 must be a number, found null \u2014 "
            "write a number in 4 numbers c3, c2, c1, c0");
  EXPECT_EQ(ErrorOf(PaperWith("\"source\": \"paper eq. (3)\"", "\"source\": 3")),
            "p.json:14:7: joint1.compliance.source must be a string, found number \u2014 write it "
            "in double quotes");
  EXPECT_EQ(ErrorOf(PaperWith("\"form\": \"inverse_cubic\",\n      \"coefficients\": [639",
                              "\"form\": \"inverse\",\n      \"coefficients\": [639")),
            "p.json:12:7: joint1.compliance.form is 'inverse' \u2014 write \"inverse_cubic\" (the "
            "paper's 1/K(L), N·m/rad), \"direct_cubic\" (K(L), rad/(N·m)) or \"beam_series\" "
            "(docs/identification.md)");
  EXPECT_EQ(ErrorOf(PaperWith("\"format\": \"pliant-parameters\"", "\"format\": \"other\"")),
            "p.json:2:3: format is 'other', not 'pliant-parameters' \u2014 this is not a pliant "
            "parameters file; start from data/paper.json");
  EXPECT_EQ(ErrorOf(PaperWith("\"version\": 1", "\"version\": 2")),
            "p.json:3:3: version 2 is not supported \u2014 this pliant reads version 1; write "
            "\"version\": 1 with the fields of docs/parameters.md");
}

TEST(ParametersJson, ValidationFailuresPointAtTheField) {
  const std::string text = PaperWith("\"value\": 0.008478", "\"value\": 0.5");
  EXPECT_EQ(ErrorOf(text),
            "p.json:16:5: joint1: backlash_rad must be in [0, 0.1) rad \u2014 "
            "correct the value" +
                kSeeDocs);
  // The paper's 1/K2 crosses zero near 0.014 m: a range reaching below it is refused.
  const std::string range = PaperWith(
      "\"value\": [0.09, 0.22],\n      \"source\": \"paper section 3: 14 depths from 0.09 to 0.22 "
      "m\"\n    }\n  }\n}",
      "\"value\": [0.01, 0.22]\n    }\n  }\n}");
  const std::string message = ErrorOf(range);
  EXPECT_TRUE(std::regex_match(message, std::regex("p\\.json:39:5: joint2: the compliance cubic "
                                                   "reaches -[0-9.]+ on the valid depth range "
                                                   "\\[0\\.01, 0\\.22\\] m.*")))
      << message;
  // No deadzone_width_nm key: the error points at the joint.
  const std::string zero = PaperWith(
      "\"value\": 0.1,\n      \"source\": \"paper section 2, after eq. (2)\"\n    },\n    "
      "\"deadzone_width_nm\": {\n      \"value\": 0.1,\n      \"source\": \"pliant default: the "
      "dead-zone is taken up at the paper's tau_min\"\n    },",
      "\"value\": 0\n    },");
  EXPECT_EQ(ErrorOf(zero),
            "p.json:5:3: joint1: deadzone_width_nm must be in (0, 10) N·m \u2014 "
            "correct the value" +
                kSeeDocs);
}

TEST(ParametersJson, CovarianceChecks) {
  const std::string end = "\n  }\n}\n";
  const auto with = [&](const std::string& covariance) {
    return PaperWith(end, "\n  },\n  \"covariance\": " + covariance + "\n}\n");
  };
  const std::string ok = with("{\"names\": [\"joint1.backlash_rad\"], \"matrix\": [[1e-6]]}");
  EXPECT_EQ(ParseParameters(ok, "p.json").covariance->matrix(0, 0), 1e-6);
  EXPECT_EQ(ErrorOf(with("{\"names\": [\"a\", \"a\"], \"matrix\": [[1, 0], [0, 1]]}")),
            "p.json:61:33: covariance.names lists 'a' twice \u2014 name each parameter once");
  EXPECT_EQ(ErrorOf(with("{\"names\": [\"a\", \"b\"], \"matrix\": [[1, 0]]}")),
            "p.json:61:39: covariance.matrix must have one row per name (2) \u2014 write an n×n "
            "array of arrays, in the order of covariance.names");
  EXPECT_EQ(ErrorOf(with("{\"names\": [\"a\", \"b\"], \"matrix\": [[1, 0], [0.5, 1]]}")),
            "p.json:61:3: covariance must be symmetric \u2014 correct the value" + kSeeDocs);
}

TEST(ParametersJson, SyntaxErrorsAndDuplicateKeysHaveLineAndColumn) {
  EXPECT_EQ(ErrorOf(PaperWith("\"version\": 1,", "\"version\": 1")),
            "p.json:4:15: not valid JSON: syntax error while parsing object - unexpected string "
            "literal; expected '}' \u2014 fix the syntax here; a missing comma, quote or bracket "
            "is the usual cause");
  EXPECT_EQ(ErrorOf(PaperWith("\"value\": 0.008478,", "\"value\": 0.008478, \"value\": 0.1,")),
            "p.json:17:26: duplicate key 'value' in joint1.backlash_rad \u2014 keep only one; JSON "
            "readers silently use the last and ignore the others");
}

// Fuzzing found that a number too large for a double escaped as nlohmann's
// out_of_range instead of an InputError (tests/fuzz/regressions/parameters/).
TEST(ParametersJson, NumberTooLargeForADoubleIsAnInputError) {
  EXPECT_EQ(ErrorOf(PaperWith("\"value\": 0.008478,", "\"value\": 1e400,")),
            "p.json:17:16: number 1e400 does not fit in a double \u2014 write a number between "
            "-1.7e308 and 1.7e308");
  const std::string fuzzed =
      ReadText(std::string(PLIANT_SOURCE_DIR) + "/tests/fuzz/regressions/parameters/number_overflow.json");
  EXPECT_NE(ErrorOf(fuzzed).find("does not fit in a double"), std::string::npos) << ErrorOf(fuzzed);
}

// The paper's numbers are written twice: in data/paper.json, with their
// sources, and in models::PaperParameters() for code. They must agree.
TEST(ParametersJson, PaperFileAgreesWithTheLibrarysPaperParameters) {
  const models::ModelParameters file = ReadParameters(kPaperPath);
  const models::ModelParameters code = models::PaperParameters();
  for (int j = 0; j < 2; ++j) {
    const auto &a = file.joints[j], &b = code.joints[j];
    EXPECT_EQ(a.compliance.form, b.compliance.form) << j;
    EXPECT_EQ(a.compliance.cubic.coefficients, b.compliance.cubic.coefficients) << j;
    EXPECT_EQ(a.backlash_rad, b.backlash_rad) << j;
    EXPECT_EQ(a.tau_min_nm, b.tau_min_nm) << j;
    EXPECT_EQ(a.deadzone_width_nm, b.deadzone_width_nm) << j;
    EXPECT_EQ(a.depth_min_m, b.depth_min_m) << j;
    EXPECT_EQ(a.depth_max_m, b.depth_max_m) << j;
    EXPECT_EQ(a.bias_torque.angle_rad, b.bias_torque.angle_rad) << j;
    EXPECT_EQ(a.bias_torque.torque_nm, b.bias_torque.torque_nm) << j;
  }
}

}  // namespace
}  // namespace pliant::io
