#include "pliant/estimation/log_correction.h"

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "paper_parameters.h"
#include "pliant/io/input_error.h"
#include "run_command.h"

namespace pliant::estimation {
namespace {

namespace fs = std::filesystem;

// No bias and K = 0.05 rad/(N·m): every corrected value is checkable by hand.
ComplianceCorrector HandCorrector() {
  models::ModelParameters p = models::testing::PaperParameters();
  for (auto& joint : p.joints) {
    joint.bias_torque = {{0.0}, {0.0}};
    joint.compliance.cubic.coefficients = {0.0, 0.0, 0.0, 20.0};
  }
  return ComplianceCorrector(p, CorrectionModel::kPaper);
}

TEST(CorrectLog, AddsCorrectedColumnsAndMeasuresAgainstTheTruth) {
  const fs::path dir = testing::FreshDirectory("log_correction");
  std::ofstream(dir / "in.csv") << "# arm: PSM2\n"
                                   "t,q1,q2,q3,tau1,tau2,q1_true,q2_true,temp\n"
                                   "0,0.1,0.2,0.15,1.0,0.0,0.041522,0.2,30\n"
                                   "0.01,0.1,0.2,0.05,0.0,-0.5,0.1,0.232176,31\n";
  const auto summary =
      CorrectLog((dir / "in.csv").string(), (dir / "out.csv").string(), HandCorrector(), "note");
  EXPECT_EQ(summary.rows, 2u);
  EXPECT_EQ(summary.depth_clamped_rows, 1u);
  EXPECT_EQ(summary.reference, "q*_true");
  // Both rows are corrected onto the truth exactly (0.1 − 0.008478 − 0.05 and
  // 0.2 + 0.007176 + 0.025), while the encoders were off by 58.5 and 32.2 mrad.
  EXPECT_LT(summary.corrected.MaxMm(), 1e-9);
  EXPECT_GT(summary.uncorrected.MaxMm(), 2.0);

  const io::Log out = io::ReadLog((dir / "out.csv").string());
  EXPECT_EQ(out.header.Metadata("arm"), "PSM2");
  EXPECT_EQ(out.header.Metadata("correction"), "note");
  EXPECT_NEAR(out.Column("q1_corr")[0], 0.041522, 1e-15);
  EXPECT_NEAR(out.Column("q2_corr")[1], 0.232176, 1e-15);
  EXPECT_EQ(out.Column("temp"), (std::vector<double>{30, 31}));
}

TEST(CorrectLog, ABadRowLeavesNoOutputAndKeepsTheOldFile) {
  const fs::path dir = testing::FreshDirectory("log_correction_bad");
  std::ofstream(dir / "in.csv") << "t,q1,q2,q3,tau1,tau2\n0,0,0,0.1,0,0\n0.01,0,0,0.1,x,0\n";
  std::ofstream(dir / "out.csv") << "old\n";
  EXPECT_THROW(
      CorrectLog((dir / "in.csv").string(), (dir / "out.csv").string(), HandCorrector(), ""),
      io::InputError);
  EXPECT_EQ(testing::ReadText(dir / "out.csv"), "old\n");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 2);
}

}  // namespace
}  // namespace pliant::estimation
