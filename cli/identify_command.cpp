// pliant identify: the compliance model from logs (estimation/identify_logs.h), written
// as a parameters file with its covariance, its summary and its figures.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "commands.h"
#include "identify_effects.h"
#include "identify_figures.h"
#include "pliant/estimation/identify_logs.h"
#include "pliant/estimation/identification_report.h"
#include "pliant/estimation/joint_smoother.h"
#include "pliant/experiments/plot.h"
#include "pliant/io/input_error.h"
#include "pliant/io/log_plausibility.h"
#include "pliant/io/output_path.h"
#include "pliant/io/parameters_json.h"
#include "summary_stream.h"

namespace pliant::cli {
namespace {

struct IdentifyOptions {
  std::vector<std::string> logs;
  std::string output_path;
  std::string method = "auto";
  bool no_held_friction = false;
  std::string law = "inverse_cubic";
  std::string prior_path;
  std::string figure_path;
  int harmonics = 2;
  bool json = false;
  bool skip_bad_rows = false;
  std::vector<std::string> effects;  ///< --effect: catalogue effects fitted after the base
};

// (CLI11 has checked the name: IsMember.)
models::ComplianceForm LawOf(const std::string& name) {
  models::ComplianceForm form = models::ComplianceForm::kInverseCubic;
  models::ComplianceFormNamed(name, &form);
  return form;
}

// The paper's Fig. 6: per-depth 1/K, the fitted law and its 95 % band.
void DrawFigure(const estimation::IdentificationResult& r, const std::string& path) {
  experiments::Figure figure;
  figure.title = "1/K against depth (" + r.method + ")";
  for (int j = 0; j < 2; ++j) {
    experiments::PlotPanel panel{"joint " + std::to_string(j + 1), "insertion depth L (m)",
                                 "1/K (N·m/rad)", {}};
    experiments::PlotSeries points{"per-depth estimate", {}, {}, "points pt 7 ps 0.8"};
    for (const auto& e : r.depth_estimates) {
      if (e.joint == j) points.x.push_back(e.insertion_depth_m), points.y.push_back(e.inverse_compliance_nm_per_rad);
    }
    experiments::PlotSeries law{"fitted law", {}, {}, "lines lw 2"};
    experiments::PlotSeries low{"95 % band", {}, {}, "lines dt 2 lc rgb 'gray40'"};
    experiments::PlotSeries high{"", {}, {}, "lines dt 2 lc rgb 'gray40'"};
    const auto& joint = r.parameters.joints[j];
    for (int i = 0; i <= 60; ++i) {
      const double depth = joint.depth_min_m + (joint.depth_max_m - joint.depth_min_m) * i / 60.0;
      const auto at = estimation::QueryParametersAtDepth(r.parameters, depth).joints[j];
      for (auto* s : {&law, &low, &high}) s->x.push_back(depth);
      law.y.push_back(at.inverse_compliance_nm_per_rad);
      low.y.push_back(at.inverse_compliance_nm_per_rad - 1.96 * at.inverse_compliance_sd);
      high.y.push_back(at.inverse_compliance_nm_per_rad + 1.96 * at.inverse_compliance_sd);
    }
    panel.series = {points, law, low, high};
    figure.panels.push_back(panel);
  }
  experiments::WriteFigure(figure, path);
}

void RunIdentify(const IdentifyOptions& options) {
  estimation::CheckIdentifyEffectNames(options.effects);
  io::CheckOutputFile(options.output_path, "-o");
  io::CheckOutputFile(options.figure_path, "--figure");
  const models::ModelParameters prior =
      options.prior_path.empty() ? estimation::PaperPrior() : io::ReadParameters(options.prior_path);
  for (const auto& path : options.logs) {
    io::CheckLogPlausibilityAndWarn(path, {options.skip_bad_rows});
  }
  estimation::IdentifyLogsOptions fit;
  fit.method = options.method;
  fit.law = LawOf(options.law);
  fit.bias_harmonics = options.harmonics;
  fit.held_friction = !options.no_held_friction;
  fit.effects = options.effects;
  fit.skip_bad_rows = options.skip_bad_rows;
  const auto [result, data, effects] = estimation::IdentifyLogFiles(options.logs, prior, fit);
  io::WriteParameters(options.output_path, result.parameters);
  std::FILE* out = SummaryStream(options.output_path);
  const auto laws = estimation::CompareLaws(result);
  if (options.json) {
    auto json = estimation::IdentificationJson(result, data, laws);
    json["output"] = options.output_path;
    estimation::AddEffectFitsJson(effects, &json);
    std::fprintf(out, "%s\n", json.dump(2).c_str());
  } else {
    std::fprintf(out, "pliant identify: %s%s",
                 estimation::IdentificationTable(result, data, laws).c_str(),
                 EffectFitsText(effects).c_str());
    std::fprintf(out, "  wrote %s\n", options.output_path.c_str());
  }
  for (const auto& w : result.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  if (!options.figure_path.empty()) {
    DrawFigure(result, options.figure_path);
    DrawDataFigures(data, options.figure_path);
  }
}

}  // namespace

Command AddIdentifyCommand(CLI::App& app) {
  auto options = std::make_shared<IdentifyOptions>();
  CLI::App* sub = app.add_subcommand(
      "identify", "Identify compliance, backlash and bias torque from logs (docs/identification.md)");
  sub->add_option("logs", options->logs, "Logs (CSV): free-tip rows feed the bias, tip_fixed rows "
                                         "the compliance and backlash")
      ->required();
  sub->add_option("-o,--output", options->output_path, "Parameters file to write (JSON), atomically")
      ->required();
  sub->add_option("--method", options->method,
                  "paper: the paper's procedure; smoother: one Ceres problem with covariance; "
                  "quasi_static: clamp by clamp with the held friction (auto: quasi_static when "
                  "a log records a single joint, else smoother)")
      ->check(CLI::IsMember({"auto", "paper", "smoother", "quasi_static"}))
      ->capture_default_str();
  sub->add_option("--model", options->law, "Compliance law K(L)")
      ->check(CLI::IsMember({"inverse_cubic", "direct_cubic", "beam_series"}))
      ->capture_default_str();
  sub->add_option("--prior", options->prior_path,
                  "Parameters the priors are centred on (default: the paper's, data/paper.json)");
  sub->add_option("--harmonics", options->harmonics, "Fourier harmonics of the bias torque")
      ->check(CLI::Range(0, 6))
      ->capture_default_str();
  sub->add_option("--figure", options->figure_path,
                  "Also draw 1/K against depth with the law and its 95 % band (.png or .svg), and beside it the data: _fig4 (free-tip effort per depth), _fig5 (a clamped loop)");
  sub->add_flag("--no-held-friction", options->no_held_friction,
                "quasi_static: fit the paper's form only (no held_friction effect)");
  sub->add_option("--effect", options->effects,
                  "Catalogue effect to fit after the base model, into the file's effects: the "
                  "arm's dynamics (joint_inertia, joint_friction) on the logs' free motion, "
                  "others on the held-tip rows with each joint's K scale and clearance "
                  "(repeatable; docs/effects.md)");
  sub->add_flag("--json", options->json, "Print the results as JSON");
  sub->add_flag("--skip-bad-rows", options->skip_bad_rows,
                "Drop and count rows with NaN/Inf/empty required values instead of stopping");
  return [options] { RunIdentify(*options); };
}

}  // namespace pliant::cli
