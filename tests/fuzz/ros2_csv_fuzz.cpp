// libFuzzer target: any bytes given to the ROS 2 extractor CSV importer, as a
// measured_js file, end in a log whose t starts at 0 and increases and whose
// q3 lies in 0-0.3 m, or in an InputError; never a crash, a hang or another
// exception.
#include <cstdlib>

#include "fuzz_input.h"
#include "pliant/io/import.h"
#include "pliant/io/input_error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static pliant::fuzz::MemoryFile file;
  const std::string& path = file.Hold(data, size);
  try {
    const pliant::io::Log log = pliant::io::ImportRos2Csv({path}, {0, "measured_js"});
    const int t = log.header.Index("t"), q3 = log.header.Index("q3");
    if (log.Rows() == 0 || log.Value(0, t) != 0.0) std::abort();
    for (std::size_t r = 0; r < log.Rows(); ++r) {
      if (r > 0 && !(log.Value(r, t) > log.Value(r - 1, t))) std::abort();
      if (!(log.Value(r, q3) >= 0.0 && log.Value(r, q3) <= 0.3)) std::abort();
    }
  } catch (const pliant::io::InputError&) {
  }
  return 0;
}
