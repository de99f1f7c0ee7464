#pragma once
// Each subcommand registers its options on the app and returns the function
// that runs it. Commands throw io::InputError for bad input (exit 2) and any
// other exception for runtime failures (exit 1).

#include <functional>

#include <CLI/CLI.hpp>

namespace pliant::cli {

using Command = std::function<void()>;

Command AddCorrectCommand(CLI::App& app);
Command AddIdentifyCommand(CLI::App& app);
Command AddParamsCommand(CLI::App& app);
Command AddSimulateCommand(CLI::App& app);
Command AddFilterCommand(CLI::App& app);
Command AddDiagnoseCommand(CLI::App& app);
Command AddMontecarloCommand(CLI::App& app);
Command AddImportCommand(CLI::App& app);

}  // namespace pliant::cli
