// libFuzzer target: any text given to the study reader ends in a study or in
// an InputError — never a crash, a hang or another exception. Run from the
// repository's root (scripts/fuzz.sh does), where the corpus's relative
// scenario paths resolve.
#include <cstdint>
#include <string>

#include "pliant/experiments/study.h"
#include "pliant/io/input_error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    pliant::experiments::ParseStudy(text, "fuzz.json");
  } catch (const pliant::io::InputError&) {
  }
  return 0;
}
