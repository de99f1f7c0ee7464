// The self-contained HTML report: tables and PNG plots as data URIs, so the
// one file can be mailed or attached to an issue and opens in any browser.
#include "pliant/experiments/diagnosis_report.h"

#include <unistd.h>

#include <boost/archive/iterators/base64_from_binary.hpp>
#include <boost/archive/iterators/transform_width.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "diagnosis_report_internal.h"
#include "pliant/io/atomic_file.h"

namespace pliant::experiments {
namespace {

namespace fs = std::filesystem;

std::string Base64(const std::string& bytes) {
  using namespace boost::archive::iterators;
  using Encoder = base64_from_binary<transform_width<std::string::const_iterator, 6, 8>>;
  std::string out(Encoder(bytes.begin()), Encoder(bytes.end()));
  return out.append((3 - bytes.size() % 3) % 3, '=');
}

std::string Escaped(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '&':
        out += "&amp;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string Number(const char* format, double value) {
  char text[64];
  std::snprintf(text, sizeof text, format, value);
  return text;
}

std::string ReadBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read the figure " + path);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

std::string Row(const std::vector<std::string>& cells, const char* tag = "td") {
  std::string row = "<tr>";
  for (const auto& cell : cells) row += std::string("<") + tag + ">" + cell + "</" + tag + ">";
  return row + "</tr>\n";
}

// A p-value that underflowed a double is "below the smallest double", not 0.
std::string P(double p) {
  if (p <= 0.0) return "&lt; 1e-300";
  return p < 1e-4 ? Number("%.1e", p) : Number("%.4f", p);
}

std::string StatisticsTable(const estimation::Diagnosis& d) {
  const auto& b = d.before;
  const auto& a = d.after;
  auto pair = [](const char* f, double x, double y) { return Number(f, x) + " / " + Number(f, y); };
  std::string t = "<table>\n" + Row({"", "model as given", "with the effect", "unit"}, "th");
  t += Row({"RMS error at the tip, held out", Number("%.3f", d.rms_before_mm),
            Number("%.3f", d.rms_after_mm), "mm"});
  t += Row({"of which the sensors' noise alone (no model goes below it)",
            Number("%.3f", d.noise_floor_mm), Number("%.3f", d.noise_floor_mm), "mm"});
  t += Row({"RMS residual, joint 1 / 2", pair("%.3f", 1e3 * b.rms_rad[0], 1e3 * b.rms_rad[1]),
            pair("%.3f", 1e3 * a.rms_rad[0], 1e3 * a.rms_rad[1]), "mrad"});
  t += Row({"mean residual, joint 1 / 2", pair("%.3f", 1e3 * b.bias_rad[0], 1e3 * b.bias_rad[1]),
            pair("%.3f", 1e3 * a.bias_rad[0], 1e3 * a.bias_rad[1]), "mrad"});
  // The filter runs the model as given (it has no candidate effect in it), so
  // its NIS has no "after" column.
  t += Row({"filter's mean NIS per degree of freedom (95 % band)",
            Number("%.2f", b.mean_nis) + " (" + pair("%.2f", b.nis_band[0], b.nis_band[1]) +
                ")<br>" + Escaped(detail::NisVerdict(b)),
            "—", "1 when the noise model is right"});
  t += Row({"Ljung–Box Q (p): whiteness",
            Number("%.1f", b.ljung_box_q) + " (" + P(b.ljung_box_p) + ")",
            Number("%.1f", a.ljung_box_q) + " (" + P(a.ljung_box_p) + ")", "small p: not white"});
  t += Row({"Jarque–Bera (p): normality",
            Number("%.1f", b.normality_statistic) + " (" + P(b.normality_p) + ")",
            Number("%.1f", a.normality_statistic) + " (" + P(a.normality_p) + ")",
            "small p: not Gaussian"});
  t += Row({"samples", std::to_string(b.samples), std::to_string(a.samples), ""});
  return t + "</table>\n";
}

std::string EffectsTable(const estimation::Diagnosis& d) {
  std::string t = "<table>\n" + Row({"#", "effect", "what it is", "channels", "error removed",
                                     "removed given its closest rival", "p", "ΔAIC",
                                     "held-out RMS (mm)", "size (RMS it changes)",
                                     "fitted parameters"},
                                    "th");
  int rank = 0;
  for (const auto& e : d.effects) {
    std::string channels, parameters;
    for (const auto& c : e.channels) channels += (channels.empty() ? "" : ", ") + Escaped(c);
    for (std::size_t i = 0; i < e.parameter_names.size() && i < e.parameters.size(); ++i) {
      parameters += (parameters.empty() ? "" : "<br>") + Escaped(e.parameter_names[i]) + " = " +
                    Number("%.4g", e.parameters[i]);
      if (i < e.parameter_sd.size()) parameters += " ± " + Number("%.2g", e.parameter_sd[i]);
      if (detail::AtBound(e.name, e.parameter_names[i], e.parameters[i]))
        parameters += " <em>(at its bound)</em>";
    }
    std::string name = "<code>" + Escaped(e.name) + "</code>";
    if (e.missing) name += " <strong class=\"missing\">missing</strong>";
    std::string description = Escaped(e.description);
    if (!e.indistinguishable_from.empty()) {
      std::string others;
      for (const auto& o : e.indistinguishable_from) others += (others.empty() ? "" : ", ") + o;
      description += "<br><strong>Cannot tell from " + Escaped(others) +
                     "</strong> on this log (each removes little once the other is in). To "
                     "separate them: " + Escaped(e.separating_experiment) + ".";
    }
    t += Row(
        {std::to_string(++rank), name, description, channels,
         Number("%.1f %%", 100.0 * e.score), Number("%.1f %%", 100.0 * e.unique_score),
         P(e.p_value), Number("%.1f", e.delta_aic),
         Number("%.3f", e.heldout_rms_before_mm) + " → " + Number("%.3f", e.heldout_rms_after_mm),
         Number("%.3g", e.size) + " ± " + Number("%.2g", e.size_sd) + " " + Escaped(e.size_unit),
         parameters});
  }
  return t + "</table>\n";
}

// The --add effects as fitted on every compared row: what the model now holds.
std::string AddedTable(const estimation::Diagnosis& d) {
  if (d.added.empty()) return "";
  std::string t = "<h2>Effects added to the model (<code>--add</code>), as fitted</h2>\n<table>\n" +
                  Row({"effect", "what it is", "parameter", "value ± σ"}, "th");
  for (const auto& e : d.added) {
    for (std::size_t i = 0; i < e.parameter_names.size() && i < e.parameters.size(); ++i) {
      std::string value = Number("%.4g", e.parameters[i]);
      if (i < e.parameter_sd.size()) value += " ± " + Number("%.2g", e.parameter_sd[i]);
      if (detail::AtBound(e.name, e.parameter_names[i], e.parameters[i]))
        value += " <em>(at its bound)</em>";
      t += Row({i == 0 ? "<code>" + Escaped(e.name) + "</code>" : "",
                i == 0 ? Escaped(e.description) : "", Escaped(e.parameter_names[i]), value});
    }
  }
  return t + "</table>\n";
}

std::string Notes(const estimation::Diagnosis& d, const std::vector<std::string>& missing) {
  std::string n;
  for (const auto& note : d.notes) n += "<li>" + Escaped(note) + "</li>\n";
  for (const auto& m : missing) n += "<li>A picture is missing: " + Escaped(m) + "</li>\n";
  return n.empty() ? "" : "<h2>What this log cannot tell</h2>\n<ul>\n" + n + "</ul>\n";
}

std::string ChannelsTable(const estimation::Diagnosis& d) {
  std::string t = "<table>\n" + Row({"#", "channel", "joint", "lag (samples)",
                                     "residual variance explained", "p", "in words"},
                                    "th");
  int rank = 0;
  for (const auto& c : d.channels) {
    std::string words = Escaped(c.finding);
    if (!c.remark.empty()) words += "<br><em>Note: " + Escaped(c.remark) + ".</em>";
    t += Row({std::to_string(++rank), "<code>" + Escaped(c.name) + "</code>",
              std::to_string(c.joint), std::to_string(c.lag), Number("%.1f %%", 100.0 * c.score),
              P(c.p_value), words});
  }
  return t + "</table>\n";
}

const char* kStyle = R"(<style>
body { font-family: sans-serif; margin: 2em auto; max-width: 1250px; color: #222; }
table { border-collapse: collapse; margin: 1em 0; font-size: 0.9em; }
th, td { border: 1px solid #ccc; padding: 0.3em 0.6em; text-align: left; vertical-align: top; }
th { background: #f0f0f0; }
.missing { color: #b00; }
.verdict { font-size: 1.2em; padding: 0.6em; background: #fff4e0; border-left: 4px solid #e90; }
img { max-width: 100%; border: 1px solid #ddd; }
figure { margin: 1.5em 0; }
</style>
)";

// Counts the plots the browser decoded and laid out; the Chromium test reads it.
const char* kRenderCheck = R"(<script>
window.addEventListener('load', function () {
  var n = 0;
  document.querySelectorAll('img.plot').forEach(function (img) {
    var box = img.getBoundingClientRect();
    if (img.complete && img.naturalWidth > 0 && box.width > 0 && box.height > 0) n++;
  });
  document.getElementById('render-check').setAttribute('data-rendered', String(n));
});
</script>
)";

// What each plot of WriteDiagnosisFigures shows, for its caption.
std::string Caption(const std::string& file) {
  if (file == "residual_time.png")
    return "The residual (model's joint angle minus where the tip was) over the log, before and "
           "after: a right model leaves noise around zero.";
  if (file == "residual_channels.png")
    return "The residual against the channels that explain most of its variance (at their best "
           "lag): a trend here names what the model misses.";
  if (file == "fig5_residual_effort.png")
    return "The residual against the measured effort, per joint (the paper's Fig. 5 plots effort "
           "against angle on the clamped beam): a slope or a loop is a load effect the model "
           "lacks.";
  if (file == "fig7_fig8_worst_segment.png")
    return "The worst segment of each joint over time (the paper's Figs. 7, 8: the tip is held, so "
           "the corrected angle should stay constant).";
  return file;
}

}  // namespace

std::string DiagnosisReportHtml(const io::Log& log, const estimation::Diagnosis& d,
                                const DiagnosisReportSources& sources,
                                const std::vector<std::string>& figure_paths,
                                const std::vector<std::string>& missing_figures) {
  std::ostringstream h;
  h << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
    << "<title>pliant diagnose — " << Escaped(sources.log_path) << "</title>\n"
    << kStyle << kRenderCheck << "</head>\n<body>\n"
    << "<h1>Where the model fails: " << Escaped(sources.log_path) << "</h1>\n"
    << "<p>Parameters <code>" << Escaped(sources.parameters_path)
    << "</code>; residual against <code>" << Escaped(d.reference) << "</code> over "
    << d.series.row.size() << " of " << log.Rows() << " rows";
  if (!d.added_effects.empty()) {
    h << "; effects added (<code>--add</code>):";
    for (const auto& name : d.added_effects) h << " <code>" << Escaped(name) << "</code>";
  }
  h << ".</p>\n<p class=\"verdict\">";
  if (d.missing_effect) {
    h << "Missing effect: <strong><code>" << Escaped(*d.missing_effect) << "</code></strong>. ";
  } else {
    h << "No candidate effect is significantly missing. ";
  }
  h << "Held-out RMS error at the tip " << Number("%.3f", d.rms_before_mm) << " mm → "
    << Number("%.3f", d.rms_after_mm) << " mm.</p>\n"
    << Notes(d, missing_figures) << AddedTable(d) << "<h2>Before and after</h2>\n"
    << StatisticsTable(d) << "<h2>Candidate effects, best first</h2>\n"
    << "<p>Each candidate is fitted as an extension of the model; \"error removed\" is the "
       "held-out RMS reduction (segments the fit did not see), \"removed given its closest "
       "rival\" what it still removes when fitted together with the candidate that explains most "
       "of the same residual, p the significance of the held-out gain with the segments as "
       "the independent units, adjusted for the candidates tried; \"size\" is the RMS at the "
       "tip of what the fitted effect changes in the residual, so a larger size goes with a "
       "larger in-sample reduction (method: docs/diagnose-method.md).</p>\n"
    << EffectsTable(d) << "<h2>Channels that explain the residual, best first</h2>\n"
    << ChannelsTable(d) << "<h2>Plots</h2>\n";
  for (const auto& path : figure_paths) {
    const std::string name = fs::path(path).filename().string();
    h << "<figure><img class=\"plot\" alt=\"" << Escaped(name) << "\" src=\"data:image/png;base64,"
      << Base64(ReadBytes(path)) << "\"><figcaption>" << Escaped(Caption(name))
      << "</figcaption></figure>\n";
  }
  h << "<div id=\"render-check\" data-expected=\"" << figure_paths.size()
    << "\" data-rendered=\"0\"></div>\n</body>\n</html>\n";
  return h.str();
}

DiagnosisReportFiles WriteDiagnosisReport(const std::string& dir, const io::Log& log,
                                          const estimation::Diagnosis& d,
                                          const DiagnosisReportSources& sources) {
  fs::create_directories(fs::path(dir) / "figures");
  // Draw into a private directory first, then publish each file atomically.
  std::string scratch = (fs::temp_directory_path() / "pliant-report-XXXXXX").string();
  if (!mkdtemp(scratch.data())) throw std::runtime_error("cannot make a temporary directory");
  DiagnosisReportFiles files;
  try {
    const auto drawn = WriteDiagnosisFigures(scratch, log, d, &files.missing_figures);
    for (const auto& path : drawn) {
      files.figures.push_back((fs::path(dir) / "figures" / fs::path(path).filename()).string());
      io::WriteFileAtomically(files.figures.back(), ReadBytes(path));
    }
    files.summary_json = (fs::path(dir) / "summary.json").string();
    io::WriteFileAtomically(files.summary_json, DiagnosisSummaryJson(d).dump(2) + "\n");
    files.html = (fs::path(dir) / "index.html").string();
    io::WriteFileAtomically(files.html,
                            DiagnosisReportHtml(log, d, sources, drawn, files.missing_figures));
  } catch (...) {
    std::error_code ignored;
    fs::remove_all(scratch, ignored);
    throw;
  }
  std::error_code ignored;
  fs::remove_all(scratch, ignored);
  return files;
}

}  // namespace pliant::experiments
