// my_pliant: the whole pliant command line, with one more effect in the
// catalogue — simulate, identify, filter and diagnose all know it by name.
#include <pliant/cli/run.h>
#include <pliant/estimation/effect_catalogue.h>

#include "one_sided_compliance.h"

int main(int argc, char** argv) {
  pliant::estimation::EffectCatalogue::Global().Add<OneSidedCompliance>();
  return pliant::cli::Run(argc, argv);
}
