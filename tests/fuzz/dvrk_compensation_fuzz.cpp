// libFuzzer target: any text given to the dVRK compensation-file reader ends in
// an InputError, or in six entries whose write–read round trip is bit-exact
// and whose conversion to pliant's parameters is usable or an InputError.
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "pliant/io/dvrk_compensation.h"
#include "pliant/io/input_error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  pliant::io::DvrkCompensation compensation;
  try {
    compensation = pliant::io::ParseDvrkCompensation(text, "fuzz.json");
  } catch (const pliant::io::InputError&) {
    return 0;
  }
  const auto again = pliant::io::ParseDvrkCompensation(
      pliant::io::DvrkCompensationText(compensation), "round-trip.json");
  // memcmp: bit-exact, and NaN-proof (JSON holds none, so none may appear).
  if (std::memcmp(&again, &compensation, sizeof compensation) != 0) std::abort();
  try {
    const auto parameters = pliant::io::DvrkToParameters(compensation, "fuzz.json");
    if (!pliant::models::ValidateParameters(parameters).empty()) std::abort();
    std::vector<std::string> notes;
    pliant::io::ParametersToDvrk(parameters, &notes);
  } catch (const pliant::io::InputError&) {
  }
  return 0;
}
