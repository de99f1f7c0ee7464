// Regenerates data/divot_push.csv (see data/README.md):
//   make_sample_data data/paper.json data/divot_push.csv
#include <cstdio>
#include <exception>

#include "pliant/experiments/quasi_static_push.h"
#include "pliant/io/input_error.h"
#include "pliant/io/log_writer.h"
#include "pliant/io/parameters_json.h"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s PARAMS.json OUT.csv\n", argv[0]);
    return 2;
  }
  try {
    const auto truth = pliant::io::ReadParameters(argv[1]);
    const auto scenario = pliant::experiments::DefaultDivotScenario(truth);
    pliant::io::WriteLog(argv[2], pliant::experiments::GenerateDivotPushLog(scenario));
  } catch (const pliant::io::InputError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "make_sample_data: %s\n", e.what());
    return 1;
  }
  return 0;
}
