// The pliant command line: registers every subcommand and runs the one asked for.
#include "pliant/cli/run.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <exception>
#include <map>
#include <string>
#include <vector>

#include <glog/logging.h>

#include "commands.h"
#include "pliant/io/input_error.h"
#include "pliant/io/progress.h"

namespace pliant::cli {
namespace {

std::size_t EditDistance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t k = 0; k <= b.size(); ++k) row[k] = k;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t k = 1; k <= b.size(); ++k) {
      const std::size_t above = row[k];
      row[k] = std::min({row[k] + 1, row[k - 1] + 1, diagonal + (a[i - 1] == b[k - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

// CLI11 says "The following argument was not expected: --smoth"; say which
// option was meant, from the nearest of the command's own names.
void SuggestOptions(CLI::App& app, int argc, char** argv) {
  CLI::App* sub = nullptr;
  for (CLI::App* candidate : app.get_subcommands({})) {
    if (argc > 1 && candidate->get_name() == argv[1]) sub = candidate;
  }
  if (sub == nullptr) return;
  for (int i = 2; i < argc; ++i) {
    const std::string given = std::string(argv[i]).substr(0, std::string(argv[i]).find('='));
    if (given.size() < 2 || given[0] != '-' || given == "--") continue;
    if (sub->get_option_no_throw(given) != nullptr || given == "-h" || given == "--help") continue;
    std::string best;
    std::size_t best_distance = 3;  // at most two edits, and a third of the name
    for (const CLI::Option* option : sub->get_options()) {
      for (const std::string& name : option->get_lnames()) {
        const std::size_t d = EditDistance(given, "--" + name);
        if (d < best_distance && 3 * d <= name.size() + 2) best = "--" + name, best_distance = d;
      }
    }
    if (!best.empty()) {
      std::fprintf(stderr, "pliant %s: unknown option '%s' — did you mean '%s'?\n", argv[1],
                   given.c_str(), best.c_str());
    }
  }
}

// Ceres reports through glog ("Logging before InitGoogleLogging", "rank
// deficient"); pliant says what matters in its own words (the solver's summary,
// the identifiability warnings), so the library's log stays off the terminal.
void QuietLibraryLogs() {
  FLAGS_logtostderr = true;  // never log files in /tmp
  FLAGS_minloglevel = google::GLOG_FATAL;
  if (!google::IsGoogleLoggingInitialized()) google::InitGoogleLogging("pliant");
}

}  // namespace

int Run(int argc, char** argv) {
  QuietLibraryLogs();
  CLI::App app{"pliant — compliance and backlash estimation for the dVRK PSM"};
  app.set_version_flag("--version", std::string("pliant ") + PLIANT_VERSION);
  app.require_subcommand(1);
  std::map<CLI::App*, pliant::cli::Command> commands;
  auto add = [&](pliant::cli::Command (*make)(CLI::App&)) {
    const std::size_t before = app.get_subcommands({}).size();
    pliant::cli::Command run = make(app);
    commands[app.get_subcommands({})[before]] = std::move(run);
  };
  add(pliant::cli::AddCorrectCommand);
  add(pliant::cli::AddIdentifyCommand);
  add(pliant::cli::AddParamsCommand);
  add(pliant::cli::AddSimulateCommand);
  add(pliant::cli::AddFilterCommand);
  add(pliant::cli::AddDiagnoseCommand);
  add(pliant::cli::AddMontecarloCommand);
  add(pliant::cli::AddImportCommand);
  // Progress goes to a terminal only (io/include/pliant/io/progress.h); --quiet
  // silences it there too.
  bool quiet = false;
  for (CLI::App* sub : app.get_subcommands({})) {
    sub->add_flag("-q,--quiet", quiet, "No progress on the terminal (it is never shown when "
                                       "standard error is piped or redirected)");
  }

  // CLI11 answers a mistyped command with "A subcommand is required"; name it.
  if (argc > 1 && argv[1][0] != '-' && !commands.empty()) {
    std::string known;
    bool found = false;
    for (const CLI::App* sub : app.get_subcommands({})) {
      found = found || sub->get_name() == argv[1];
      known += (known.empty() ? "" : ", ") + sub->get_name();
    }
    if (!found) {
      std::fprintf(stderr, "pliant: unknown command '%s' — use one of: %s (pliant --help)\n",
                   argv[1], known.c_str());
      return 2;
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    if (code != 0) SuggestOptions(app, argc, argv);
    return code == 0 ? 0 : 2;  // usage errors exit 2, like bad input
  }
  pliant::io::Progress::Enable(pliant::io::Progress::ShowProgressOn(STDERR_FILENO, quiet));
  try {
    for (auto* sub : app.get_subcommands()) commands.at(sub)();
  } catch (const pliant::io::InputError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "pliant: %s\n", e.what());
    return 1;
  }
  return 0;
}

}  // namespace pliant::cli
