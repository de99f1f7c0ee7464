// pliant filter: the online EKF over a log (streamed), or the RTS smoother
// over the whole log (--smooth), written atomically with the filter's columns.
#include <cstdint>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "commands.h"
#include "pliant/estimation/filter_log.h"
#include "pliant/estimation/log_tare.h"
#include "pliant/io/input_error.h"
#include "pliant/io/log_plausibility.h"
#include "pliant/io/output_path.h"
#include "pliant/io/parameters_json.h"
#include "pliant/io/progress.h"
#include "summary_stream.h"

namespace pliant::cli {
namespace {

struct FilterCommandOptions {
  std::string params_path;
  std::string input_path;
  std::string output_path;
  bool smooth = false;
  bool skip_bad_rows = false;
  std::string tare;  // "" (none), "auto" or "T0:T1"
  estimation::FilterOptions filter;
  bool effort_offset_given = false;
};

void PrintAccuracy(std::FILE* out, const char* label, const estimation::TipErrorStatistics& s) {
  std::fprintf(out, "    %-20s RMS %7.3f mm   max %7.3f mm\n", label, s.RmsMm(), s.MaxMm());
}

void PrintSummary(const FilterCommandOptions& o, const estimation::LogFilterSummary& s) {
  std::FILE* out = SummaryStream(o.output_path);
  std::fprintf(out, "pliant filter: %zu rows%s -> %s\n", s.rows, s.smoothed ? ", RTS smoothed" : "",
               o.output_path.c_str());
  if (s.skipped_rows > 0)
    std::fprintf(out, "  skipped %zu bad rows (--skip-bad-rows)\n", s.skipped_rows);
  for (const auto& note : s.notes) std::fprintf(out, "  %s\n", note.c_str());
  for (const auto& note : s.advice) std::fprintf(out, "  %s\n", note.c_str());
  std::fprintf(out, "  mean NIS per measurement %.3f (1 when the noise model is right)\n",
               s.mean_nis_per_dof);
  std::fprintf(out,
               "  rows flagged: rejected %zu, missing %zu, depth out of range %zu, "
               "effort saturated %zu, model mismatch %zu\n",
               s.rejected_rows, s.missing_rows, s.depth_out_of_range_rows, s.saturated_rows,
               s.mismatch_rows);
  if (s.depth_out_of_range_rows > 0) {
    std::fprintf(stderr,
                 "warning: %zu rows have an insertion depth outside the parameters' valid range; "
                 "K(L) used the nearest valid depth for them\n",
                 s.depth_out_of_range_rows);
  }
  if (s.reference.empty() || s.filtered.count() == 0) return;
  std::fprintf(out, "  tip error against %s over %zu rows:\n", s.reference.c_str(),
               s.filtered.count());
  PrintAccuracy(out, "uncorrected", s.uncorrected);
  PrintAccuracy(out, "filter", s.filtered);
  if (s.smoothed) PrintAccuracy(out, "smoother", s.smoothed_error);
}

// FilterOptions::IsValid names the C++ field ("FilterOptions::gate_probability = 1.5 must
// lie in ... — fix"); a user of the command gave an option, so name that and exit 2.
io::InputError OptionError(const std::string& error) {
  static const std::pair<const char*, const char*> kOptions[] = {
      {"effort_noise_nm", "--effort-noise"},    {"encoder_noise_rad", "--encoder-noise"},
      {"external_torque_rate_nm", "--torque-rate"}, {"compliance_scale_sd", "--compliance-sd"},
      {"gate_probability", "--gate"},            {"mismatch_window", "--mismatch-window"},
      {"inertial_torque_error", "--inertial-error"}, {"unloaded_start_s", "--unloaded-start"},
      {"reference_noise_rad", "--fuse-reference"}, {"motor_inertia_kg_m2", "--motor-inertia"}};
  std::string problem = error;
  const std::string prefix = "FilterOptions::";
  if (problem.rfind(prefix, 0) == 0) problem.erase(0, prefix.size());
  std::string option = "filter options";
  for (const auto& [field, name] : kOptions) {
    if (problem.rfind(field, 0) == 0) option = name;
  }
  std::string fix = "see pliant filter --help";
  const std::size_t dash = problem.find(" \u2014 ");
  if (dash != std::string::npos) {
    fix = problem.substr(dash + std::string(" \u2014 ").size());
    problem.erase(dash);
  }
  return io::InputError(option, 0, 0, problem, fix);
}

// The unloaded start must leave loaded rows to correct: a window as long as
// the log would take every push for rest.
void CheckUnloadedStart(double unloaded_start_s, double duration_s) {
  if (unloaded_start_s > 0.0 && unloaded_start_s >= duration_s) {
    char problem[160];
    std::snprintf(problem, sizeof problem,
                  "unloaded_start_s = %g s is not shorter than the log, which lasts %g s",
                  unloaded_start_s, duration_s);
    throw io::InputError("--unloaded-start", 0, 0, problem,
                         "give the seconds at the log's start with the instrument untouched and "
                         "the arm still, e.g. 0.1, or 0 for none");
  }
}

void RunFilter(FilterCommandOptions o) {
  // A tare needs an offset to learn: unless told its σ, β is on, its σ the
  // parameters' (filter.h: NaN), as --effort-offset-sd nan would ask.
  if (o.filter.unloaded_start_s > 0.0 && !o.effort_offset_given) {
    o.filter.effort_offset_sd_nm.setConstant(estimation::FilterOptions::kFromParameters);
  }
  io::CheckOutputFile(o.output_path, "-o");
  auto parameters = io::ReadParameters(o.params_path);
  std::string error;
  if (!o.filter.IsValid(&error) ||
      !(error = estimation::OptionsAgainstParameters(parameters, o.filter)).empty()) {
    throw OptionError(error);
  }
  const auto log = io::CheckLogPlausibilityAndWarn(o.input_path, {o.skip_bad_rows});
  CheckUnloadedStart(o.filter.unloaded_start_s, log.DurationS());
  // The same tare as pliant correct's, written into the parameters' bias.
  const auto tare = o.tare.empty() ? estimation::LogTare{}
                                    : estimation::TareOnLog(o.input_path, o.tare, &parameters);
  const std::string note = tare.Note();
  std::optional<io::Progress> progress(std::in_place, "pliant filter");
  const auto summary = estimation::FilterLog(
      o.input_path, o.output_path, parameters, o.filter, o.smooth,
      "pliant filter, parameters " + o.params_path + (note.empty() ? "" : ", " + note),
      {o.skip_bad_rows});
  progress.reset();  // the line is erased before the summary
  PrintSummary(o, summary);
  std::printf("%s", tare.Words().c_str());
}

}  // namespace

Command AddFilterCommand(CLI::App& app) {
  auto o = std::make_shared<FilterCommandOptions>();
  CLI::App* sub = app.add_subcommand(
      "filter",
      "Online EKF over a log: corrected joints 1-2 with covariance, tip correction, NIS, flags "
      "(docs/filter.md)");
  sub->add_option("--params", o->params_path, "Parameters file (JSON, docs/parameters.md)")
      ->required();
  sub->add_option("input", o->input_path, "Input log (CSV, docs/log-format.md)")->required();
  sub->add_option("-o,--output", o->output_path, "Output log, written atomically")->required();
  sub->add_flag("--smooth", o->smooth,
                "RTS smoother over the whole log (holds it in memory) instead of streaming");
  sub->add_flag("--skip-bad-rows", o->skip_bad_rows,
                "Drop and count rows with NaN/Inf/empty required values instead of stopping");
  auto& f = o->filter;
  sub->add_option("--effort-noise", f.effort_noise_nm, "Effort noise σ, N·m")
      ->capture_default_str();
  sub->add_flag("--effort-noise-from-log", f.effort_noise_from_log,
                "Raise the effort noise to the log's own white noise where that is larger "
                "(the summary notes it either way)");
  sub->add_option("--encoder-noise", f.encoder_noise_rad, "Encoder noise σ, rad")
      ->capture_default_str();
  sub->add_option("--torque-rate", f.external_torque_rate_nm,
                  "Process noise of the external torque, N·m/√s")
      ->capture_default_str();
  sub->add_option("--compliance-sd", f.compliance_scale_sd,
                  "Prior σ of the compliance scale (1 = the parameters' K(L))")
      ->capture_default_str();
  sub->add_option_function<double>(
      "--fuse-reference",
      [&f](double sd_rad) {
        f.fuse_log_reference = true;
        f.reference_noise_rad = sd_rad;
      },
      "Take the log's q1_ref, q2_ref columns (a tracker) as measurements of the tip with this "
      "noise σ, rad (default: not fused; they only score the output, docs/filter.md)");
  sub->add_option("--gate", f.gate_probability,
                  "Probability a measurement the model explains passes the χ² gate")
      ->capture_default_str();
  sub->add_option("--motor-inertia", f.motor_inertia_kg_m2,
                  "Motor-side inertia J of joints 1-2, kg·m²: J·θ̈ is taken out of the effort "
                  "while the tip is held (0: off; the simulator's arm has 0.08). For logs at the "
                  "full 1.5 kHz rate: θ̈ cannot be estimated from a subsampled log. Not beside a parameters "
                  "file's joint_inertia, which the filter uses instead")
      ->capture_default_str();
  sub->add_option("--shaft-damping", f.shaft_damping_nm_s_per_rad,
                  "The instrument shaft's damping c_s, N·m·s/rad: with the tip held and the shaft "
                  "on its wall, c_s times the encoder's rate is taken out of the effort with J·θ̈ "
                  "(0: off; the simulator's instruments have 0.02). Given, the deflection model's "
                  "error ε drops from 0.08 to 0.04: the damping is no longer part of what it covers")
      ->capture_default_str();
  sub->add_option("--deflection-error", f.deflection_model_error,
                  "ε: the share of the deflection s·K(L)·τ the model may miss, as white encoder "
                  "noise (ε·K·τ)² (default: 0.04 with --shaft-damping, else 0.08; 0 for logs "
                  "drawn from the model itself; larger: more cautious q_sd across instruments, "
                  "docs/filter.md)");
  sub->add_flag_function(
      "--no-inertia-alignment", [&f](std::int64_t) { f.align_inertial_torque = false; },
      "With --motor-inertia: take J·θ̈ out of each effort as it comes, where the acceleration "
      "fit is ~12 ms late, instead of running the state that far behind (docs/filter.md)");
  sub->add_flag_function(
      "--no-held-load-bound", [&f](std::int64_t) { f.bound_held_load_rate = false; },
      "Let a held tip's load change as freely as a free tip's (σ_τ̇) instead of no faster than "
      "the motor bends the shaft (docs/filter.md)");
  sub->add_flag_function(
      "--no-load-following", [&f](std::int64_t) { f.load_follows_motor = false; },
      "Predict a held tip's load as a random walk instead of by the bend the motor's encoder "
      "increment puts into a shaft on its wall (docs/filter.md)");
  sub->add_flag_function(
      "--no-contact-inference", [&f](std::int64_t) { f.infer_contact = false; },
      "Read every effort residual as external load where the log's tip_fixed is 0 or absent, "
      "instead of contact being the exception (docs/decisions/contact-prior.md)");
  sub->add_flag_function(
      "--fixed-contact-rates", [&f](std::int64_t) { f.learn_contact_rates = false; },
      "Keep the contact chain's rates at their priors (a contact every 10 s of motion, lasting "
      "2 s) instead of learning them from the log (docs/decisions/contact-rates.md)");
  sub->add_flag_function(
      "--no-free-level", [&f](std::int64_t) { f.free_level = false; },
      "Without tip_fixed, do not learn the free arm's effort where it stands still (the bias "
      "table's error at that pose): judge a load against the table's whole error σ_rest "
      "instead (docs/decisions/contact-free-level.md)");
  sub->add_option("--inertial-error", f.inertial_torque_error,
                  "κ: the share of the fitted inertial torque J·θ̈ the fit may misread, as effort "
                  "variance (κ·J·θ̈)² with the tip held (0: exact; only with --motor-inertia)")
      ->capture_default_str();
  // Both joints get the same prior from the command line; NaN keeps "from the
  // parameters' covariance, else the default" (filter.h).
  sub->add_option_function<double>(
         "--clearance-sd", [&f](double sd) { f.backlash_sd_rad.setConstant(sd); },
         "σ of the clearance δ about the parameters' value, rad (default: the parameters' "
         "covariance, else 1e-3; 0: known exactly)");
  sub->add_option_function<double>(
         "--effort-offset-sd",
         [o](double sd) {
           o->filter.effort_offset_sd_nm.setConstant(sd);
           o->effort_offset_given = true;
         },
         "σ of a constant effort offset the bias torque misses, N·m (default 0: off, "
         "better on held-tip logs, docs/filter.md; nan: the parameters' covariance, else 0.02)");
  sub->add_option_function<double>(
         "--effort-offset-correlation",
         [&f](double s) { f.effort_offset_correlation_s.setConstant(s); },
         "τβ, s: the effort offset β as noise correlated over this time (a first-order "
         "Gauss–Markov process of stationary σ --effort-offset-sd), which a white model would "
         "average down over a hold (default inf: a constant offset; docs/decisions/"
         "coloured-effort-noise.md)");
  sub->add_flag_function(
      "--no-effort-colour", [&f](std::int64_t) { f.effort_colour_from_log = false; },
      "Do not carry the correlated effort noise the log's still stretches show as the effort "
      "offset β (docs/decisions/coloured-effort-noise.md)");
  CLI::Option* unloaded_start = sub->add_option("--unloaded-start", f.unloaded_start_s,
                  "Seconds at the log's start with the instrument untouched and the arm still "
                  "(e.g. before it approaches the tissue): the efforts there tare the effort "
                  "offset β, which is then on (σ from --effort-offset-sd, else the parameters' "
                  "covariance, else 0.02 N·m; 0: no such span; docs/filter.md)")
      ->capture_default_str();
  // The whole log is known offline: --tare finds (or is told) its unloaded
  // rows anywhere and tares the parameters' bias once; --unloaded-start is
  // for a stream, whose future is unknown (docs/filter.md).
  sub->add_option("--tare", o->tare,
                  "Tare the parameters' bias torque on the log's unloaded rows before filtering, "
                  "as pliant correct --tare: auto (the longest run with a steady load) or T0:T1 "
                  "(rows with t in that range, s); not with --unloaded-start or standard input")
      ->excludes(unloaded_start);
  sub->add_option("--output-step-limit", f.output_step_limit_counts,
                  "Encoder counts the corrected angle may move per step beyond the encoder's own "
                  "change (no jumps for a control loop; q_sd includes the gap; inf: off)")
      ->capture_default_str();
  sub->add_option("--mismatch-window", f.mismatch_window,
                  "Samples in the windowed NIS test for model mismatch")
      ->capture_default_str();
  return [o] { RunFilter(*o); };
}

}  // namespace pliant::cli
