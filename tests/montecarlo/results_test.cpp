// trials.csv rows and the summary (montecarlo.h): rows read back bit for bit,
// torn rows dropped, another study's directory refused, and the summary's
// statistics against hand-computed values.
#include <cstring>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "pliant/experiments/montecarlo.h"
#include "pliant/io/input_error.h"
#include "run_command.h"

namespace pliant::experiments {
namespace {

Study DivotStudy() { return ReadStudy(PLIANT_SOURCE_DIR "/experiments/studies/divot_study.json"); }

TrialResult Row(int k) {
  TrialResult r;
  r.trial = k;
  r.draw.simulation_seed = 0xFEDCBA9876543210ull + k;
  for (int q = 0; q < kSampledQuantities; ++q) r.draw.values[q] = 0.0;
  r.draw.values[kDepthM] = 0.1 + 0.001 * k;  // error rises with depth only
  for (int m = 0; m < kCorrectionMethods; ++m) r.tip_error_mm[m] = (k + 1) / 3.0 / (m + 1);
  r.nees[0] = 2.0;
  r.nees[1] = k < 90 ? 1.0 : 10.0;  // 10 of 100 beyond χ²(2, 0.95) = 5.99
  r.covered[0] = 2;
  r.covered[1] = k % 2;
  r.coverage_fraction[0] = 0.95;
  r.coverage_fraction[1] = 1.0 / 7.0;
  r.joint_coverage_fraction[0][0] = 0.9;
  r.joint_coverage_fraction[0][1] = 1.0;
  r.joint_coverage_fraction[1][0] = 1.0 / 7.0;
  r.joint_coverage_fraction[1][1] = k < 50 ? 0.0 : 2.0 / 7.0;
  r.held_samples = 1000 + k;
  return r;
}

TEST(TrialRow, ReadsBackBitForBit) {
  const TrialResult r = Row(41);
  const auto back = ParseTrialRow(FormatTrialRow(r));
  ASSERT_TRUE(back);
  EXPECT_EQ(back->trial, 41);
  EXPECT_EQ(back->draw.simulation_seed, r.draw.simulation_seed);
  EXPECT_EQ(std::memcmp(back->draw.values, r.draw.values, sizeof r.draw.values), 0);
  EXPECT_EQ(std::memcmp(back->tip_error_mm, r.tip_error_mm, sizeof r.tip_error_mm), 0);
  EXPECT_EQ(back->coverage_fraction[1], 1.0 / 7.0);
  EXPECT_EQ(std::memcmp(back->joint_coverage_fraction, r.joint_coverage_fraction,
                        sizeof r.joint_coverage_fraction), 0);
  EXPECT_EQ(back->covered[1], 1);
  EXPECT_EQ(back->held_samples, 1041);
}

TEST(TrialRow, ATornRowIsNotARow) {
  const std::string row = FormatTrialRow(Row(3));
  EXPECT_FALSE(ParseTrialRow(row.substr(0, row.size() - 1)));  // no newline: torn
  EXPECT_FALSE(ParseTrialRow(row.substr(0, row.size() / 2) + "\n"));
  EXPECT_FALSE(ParseTrialRow("3,x" + row.substr(3)));
}

TEST(TrialsFile, ResumesWithTheWholeRowsAndDropsATornOne) {
  const auto dir = testing::FreshDirectory("mc_trials_file").string();
  const Study study = DivotStudy();
  {
    TrialsFile file(dir, study);
    for (int k : {4, 0, 2}) file.Append(Row(k));
  }
  {  // a kill in the middle of writing row 3
    std::ofstream(dir + "/trials.csv", std::ios::app) << FormatTrialRow(Row(3)).substr(0, 40);
  }
  TrialsFile again(dir, study);
  EXPECT_EQ(again.finished().size(), 3u);
  EXPECT_EQ(again.Pending(6), (std::vector<int>{1, 3, 5}));
  again.Append(Row(3));
  TrialsFile third(dir, study);
  EXPECT_EQ(third.Pending(6), (std::vector<int>{1, 5}));
}

TEST(TrialsFile, RefusesAnotherStudysDirectory) {
  const auto dir = testing::FreshDirectory("mc_other_study").string();
  Study study = DivotStudy();
  { TrialsFile file(dir, study); }
  study.seed = 2;
  study.fingerprint ^= 1;
  try {
    TrialsFile file(dir, study);
    FAIL() << "accepted another study's directory";
  } catch (const io::InputError& e) {
    EXPECT_EQ(e.line(), 1u);
    EXPECT_NE(std::string(e.what()).find("another study"), std::string::npos) << e.what();
  }
}

TEST(Summary, PercentilesNeesAndCoverageMatchHandValues) {
  const Study study = DivotStudy();
  std::vector<TrialResult> rows;
  for (int k = 0; k < 100; ++k) rows.push_back(Row(k));
  const auto s = SummariseStudy(study, rows);
  // Errors (k+1)/3, k = 0..99: type-7 median (50 + 51)/6, 95th 95.05/3.
  const auto& none = s["methods"]["none"]["tip_error_mm"];
  EXPECT_NEAR(none["p50"].get<double>(), 50.5 / 3.0, 1e-12);
  EXPECT_NEAR(none["p95"].get<double>(), 95.05 / 3.0, 1e-12);
  EXPECT_NEAR(none["max"].get<double>(), 100.0 / 3.0, 1e-12);
  // Only the depth varies with the error: Spearman's ρ = 1, the dominant quantity.
  EXPECT_NEAR(s["methods"]["filter"]["rank_correlation"]["depth_m"].get<double>(), 1.0, 1e-12);
  EXPECT_EQ(s["methods"]["filter"]["dominant"], "depth_m");
  EXPECT_EQ(s["methods"]["filter"]["rank_correlation"]["backlash1_rad"].get<double>(), 0.0);
  // The error is linear in the depth: its spread explains all of the variance.
  const auto& regression = s["methods"]["filter"]["regression"];
  EXPECT_NEAR(regression["variance_share"]["depth_m"].get<double>(), 1.0, 1e-9);
  EXPECT_EQ(regression["variance_share"]["backlash1_rad"].get<double>(), 0.0);
  EXPECT_NEAR(regression["r2_linear"].get<double>(), 1.0, 1e-9);
  // χ²(200) quantiles 162.728 and 241.058 (tables), over 100 trials.
  const auto& f = s["honesty"]["filter"];
  EXPECT_NEAR(f["nees_band_95"][0].get<double>(), 1.62728, 2e-5);
  EXPECT_NEAR(f["nees_band_95"][1].get<double>(), 2.41058, 2e-5);
  EXPECT_EQ(f["nees_in_band"], true);
  EXPECT_EQ(f["coverage_95_picked_sample"].get<double>(), 1.0);
  const auto& m = s["honesty"]["smoother"];
  EXPECT_NEAR(m["nees_mean"].get<double>(), 1.9, 1e-12);
  EXPECT_NEAR(m["nees_within_chi2_95"].get<double>(), 0.9, 1e-12);
  EXPECT_NEAR(m["coverage_95_picked_sample"].get<double>(), 0.25, 1e-12);
  EXPECT_NEAR(m["coverage_95_held_samples"].get<double>(), 1.0 / 7.0, 1e-12);
  // Per joint: the mean over trials of each joint's fraction.
  EXPECT_NEAR(f["coverage_95_held_samples_by_joint"][0].get<double>(), 0.9, 1e-12);
  EXPECT_NEAR(f["coverage_95_held_samples_by_joint"][1].get<double>(), 1.0, 1e-12);
  EXPECT_NEAR(m["coverage_95_held_samples_by_joint"][0].get<double>(), 1.0 / 7.0, 1e-12);
  EXPECT_NEAR(m["coverage_95_held_samples_by_joint"][1].get<double>(), 1.0 / 7.0, 1e-12);
  EXPECT_EQ(s.dump().find("wall"), std::string::npos);  // no timing in the summary
}

}  // namespace
}  // namespace pliant::experiments
