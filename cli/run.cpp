// The pliant command line: registers every subcommand and runs the one asked for.
#include "pliant/cli/run.h"

#include <unistd.h>

#include <cstdio>
#include <exception>
#include <map>
#include <string>

#include "commands.h"
#include "pliant/io/input_error.h"
#include "pliant/io/progress.h"

namespace pliant::cli {

int Run(int argc, char** argv) {
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
