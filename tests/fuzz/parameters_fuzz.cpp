// libFuzzer target: any text given to the parameters reader ends in a valid
// parameter set that survives a write–read round trip, or in an InputError.
#include <cstdlib>
#include <string>

#include "pliant/io/input_error.h"
#include "pliant/io/parameters_json.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  pliant::models::ModelParameters parameters;
  try {
    parameters = pliant::io::ParseParameters(text, "fuzz.json");
  } catch (const pliant::io::InputError&) {
    return 0;
  }
  if (!pliant::models::ValidateParameters(parameters).empty()) std::abort();
  const std::string written = pliant::io::ParametersToJson(parameters).dump();
  const auto again = pliant::io::ParseParameters(written, "round-trip.json");
  if (pliant::io::ParametersToJson(again) != pliant::io::ParametersToJson(parameters)) std::abort();
  return 0;
}
