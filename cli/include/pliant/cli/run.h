#pragma once
// The pliant command as a library call, so a program of your own can register
// its effects and then be the whole pliant command line
// (docs/tutorial-missing-effect.md):
//
//   int main(int argc, char** argv) {
//     pliant::estimation::EffectCatalogue::Global().Add<MyEffect>();
//     return pliant::cli::Run(argc, argv);
//   }
//
// Exit status: 0 success, 2 bad input or usage (docs/errors.md), 1 runtime failure.

namespace pliant::cli {

int Run(int argc, char** argv);

}  // namespace pliant::cli
