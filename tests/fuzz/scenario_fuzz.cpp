// libFuzzer target: any text given to the scenario reader ends in a scenario
// or in an InputError — never a crash, a hang or another exception. The first
// line, when it reads 'set key=value', is applied as a --set override.
#include <string>
#include <vector>

#include "pliant/experiments/scenario.h"
#include "pliant/io/input_error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string text(reinterpret_cast<const char*>(data), size);
  std::vector<std::string> overrides;
  const std::size_t newline = text.find('\n');
  if (newline != std::string::npos && text.compare(0, 4, "set ") == 0) {
    overrides.push_back(text.substr(4, newline - 4));
    text.erase(0, newline + 1);
  }
  try {
    pliant::experiments::ParseScenario(text, "fuzz.json", overrides);
  } catch (const pliant::io::InputError&) {
  }
  return 0;
}
