#include "pliant/experiments/plot.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace pliant::experiments {
namespace {

namespace fs = std::filesystem;

// gnuplot strings in double quotes: escape what would end or break them.
std::string Quoted(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

std::string ShellQuoted(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::string Terminal(const Figure& figure, const std::string& path) {
  const std::string extension = fs::path(path).extension().string();
  std::ostringstream t;
  if (extension == ".png") {
    t << "pngcairo size " << figure.width_px << "," << figure.height_px << " font 'sans,10'";
  } else if (extension == ".svg") {
    t << "svg size " << figure.width_px << "," << figure.height_px << " font 'sans,10'";
  } else {
    throw std::runtime_error("figure " + path + ": use a .png or .svg file name");
  }
  return t.str();
}

// gnuplot stops a whole figure on a series whose every point is undefined
// ("all points y value undefined"), e.g. the residual of a joint the log does
// not record: such a series is left out, like an empty one.
bool HasFinitePoint(const PlotSeries& series) {
  for (std::size_t i = 0; i < series.x.size() && i < series.y.size(); ++i) {
    if (std::isfinite(series.x[i]) && std::isfinite(series.y[i])) return true;
  }
  return false;
}

std::string Script(const Figure& figure, const std::string& path, const std::string& data) {
  std::ostringstream s;
  s << "set terminal " << Terminal(figure, path) << "\n"
    << "set output " << Quoted(path) << "\n"
    << "set termoption noenhanced\nset grid\n"
    << "set multiplot layout 1," << figure.panels.size() << " title " << Quoted(figure.title)
    << "\n";
  int index = 0;
  for (const PlotPanel& panel : figure.panels) {
    s << "set key " << panel.legend << "\nset title " << Quoted(panel.title) << "\nset xlabel " << Quoted(panel.x_label)
      << "\nset ylabel " << Quoted(panel.y_label) << "\nplot ";
    bool first = true;
    for (const PlotSeries& series : panel.series) {
      const int block = index++;
      if (!HasFinitePoint(series)) continue;
      s << (first ? "" : ", \\\n     ") << Quoted(data) << " index " << block << " using 1:2 with "
        << series.style << " title " << Quoted(series.title);
      first = false;
    }
    if (first) s << "[0:1][0:1] -1 notitle";  // an empty frame
    s << "\n";
  }
  s << "unset multiplot\n";
  return s.str();
}

}  // namespace

std::string FindGnuplot() {
  if (const char* configured = std::getenv("PLIANT_GNUPLOT")) {
    return access(configured, X_OK) == 0 ? configured : "";
  }
  const char* path = std::getenv("PATH");
  std::istringstream directories(path ? path : "/usr/bin:/bin");
  for (std::string directory; std::getline(directories, directory, ':');) {
    const std::string candidate = (directory.empty() ? "." : directory) + "/gnuplot";
    if (access(candidate.c_str(), X_OK) == 0) return candidate;
  }
  return "";
}

void WriteFigure(const Figure& figure, const std::string& path, bool keep_sources) {
  const std::string gnuplot = FindGnuplot();
  if (gnuplot.empty()) {
    throw std::runtime_error(
        "cannot draw " + path +
        ": gnuplot was not found on the PATH — install it "
        "(Debian: apt-get install gnuplot-nox) or set PLIANT_GNUPLOT to its path");
  }
  const std::string picture = fs::absolute(path).string();
  fs::path work;
  if (keep_sources) {
    work = fs::path(picture).parent_path();
  } else {
    std::string pattern = (fs::temp_directory_path() / "pliant-plot-XXXXXX").string();
    if (!mkdtemp(pattern.data())) throw std::runtime_error("cannot make a temporary directory");
    work = pattern;
  }
  // The scratch directory goes on every way out, a throw from Script() included.
  struct RemoveOnExit {
    fs::path dir;
    ~RemoveOnExit() {
      std::error_code ignored;
      if (!dir.empty()) fs::remove_all(dir, ignored);
    }
  } scratch{keep_sources ? fs::path() : work};
  const std::string stem = keep_sources ? picture : (work / "figure").string();
  const std::string data = stem + ".dat", script = stem + ".gp", errors = stem + ".err";
  {
    std::ofstream out(data);
    out.precision(10);
    for (const PlotPanel& panel : figure.panels) {
      for (const PlotSeries& series : panel.series) {
        out << "# " << series.title << "\n";
        for (std::size_t i = 0; i < series.x.size(); ++i)
          out << series.x[i] << ' ' << series.y[i] << "\n";
        if (series.x.empty()) out << "NaN NaN\n";
        out << "\n\n";  // gnuplot's "index" counts blocks separated by two blank lines
      }
    }
    std::ofstream(script) << Script(figure, picture, data);
  }
  const std::string command =
      ShellQuoted(gnuplot) + " " + ShellQuoted(script) + " 2> " + ShellQuoted(errors);
  const int status = std::system(command.c_str());
  std::ifstream error_stream(errors);
  const std::string messages((std::istreambuf_iterator<char>(error_stream)), {});
  std::error_code ignored;
  fs::remove(errors, ignored);
  if (status != 0) {
    throw std::runtime_error("gnuplot failed to draw " + path + ": " + messages);
  }
}

}  // namespace pliant::experiments
