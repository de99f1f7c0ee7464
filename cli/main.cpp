// The pliant command: subcommands over the libraries, no logic of its own.
#include "pliant/cli/run.h"

int main(int argc, char** argv) { return pliant::cli::Run(argc, argv); }
